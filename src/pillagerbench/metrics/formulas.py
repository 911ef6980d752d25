"""The paper's metrics (§IV Evaluation Metrics) as plain functions, with 95 % confidence intervals.

Per episode i the final scores S_red,i and S_blue,i (the score at exactly the end of the episode):

    P = mean(S_red)                    points
    S = σ_blue − mean(S_blue)          sabotage; σ_blue = the blue team's mean score against do_nothing
    D = mean(S_red − S_blue)           point difference
    W = mean(1[S_red > S_blue] + 0.5·1[S_red = S_blue])   win rate

Over all opponents ("all"): P, D and W pooled over every episode, S the mean of the per-opponent S
(as upstream's collate_results). LLM: T_resp = mean latency, N_out = mean output tokens,
R_tps = mean over calls of N_out,i / T_resp,i (the paper's formula; `r_tps_total` is Σ tokens /
Σ latency as upstream printed), I = mean over episodes of the red team's iterations per player.

Confidence intervals: Student t on the mean (95 %, two-sided); for S the uncertainty of σ_blue
is added (Welch). Dash & Dine scores are multiplied by 0.1 as in the paper (SCORE_SCALE).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from pillagerbench.stats.result import results

Values = Sequence[float] | np.ndarray  # scores, one per episode

SCORE_SCALE = {"mushroom_war": 1.0, "dash_and_dine": 0.1}

# t_{0.975, df}
_T975: dict[float, float] = {
    1: 12.706,
    2: 4.303,
    3: 3.182,
    4: 2.776,
    5: 2.571,
    6: 2.447,
    7: 2.365,
    8: 2.306,
    9: 2.262,
    10: 2.228,
    11: 2.201,
    12: 2.179,
    13: 2.160,
    14: 2.145,
    15: 2.131,
    16: 2.120,
    17: 2.110,
    18: 2.101,
    19: 2.093,
    20: 2.086,
    21: 2.080,
    22: 2.074,
    23: 2.069,
    24: 2.064,
    25: 2.060,
    26: 2.056,
    27: 2.052,
    28: 2.048,
    29: 2.045,
    30: 2.042,
    40: 2.021,
    60: 2.000,
    120: 1.980,
}


def t_critical(df: float) -> float:
    """Two-sided 95 % Student t critical value (interpolated in 1/df between table entries)."""
    if not df or df < 1 or math.isnan(df):
        return float("nan")
    if df in _T975:
        return _T975[df]
    keys = sorted(_T975)
    if df > keys[-1]:
        lo, hi, tlo, thi = keys[-1], math.inf, _T975[keys[-1]], 1.959964
    else:
        lo = max(k for k in keys if k < df)
        hi = min(k for k in keys if k > df)
        tlo, thi = _T975[lo], _T975[hi]
    w = (1 / lo - 1 / df) / (1 / lo - (0 if hi == math.inf else 1 / hi))
    return tlo + w * (thi - tlo)


@dataclass(frozen=True)
class Estimate:
    mean: float
    ci: float  # half-width of the 95 % interval (nan with fewer than 2 values)
    n: int

    @property
    def se(self) -> float:
        return self.ci / t_critical(self.n - 1) if self.n > 1 and not math.isnan(self.ci) else float("nan")

    def fmt(self, digits: int = 2) -> str:
        if math.isnan(self.mean):
            return "–"
        return f"{self.mean:.{digits}f}" + ("" if math.isnan(self.ci) else f" ± {self.ci:.{digits}f}")


NAN = Estimate(float("nan"), float("nan"), 0)


def mean_ci(values: Iterable[float]) -> Estimate:
    x = np.asarray(list(values), dtype=float)
    x = x[~np.isnan(x)]
    n = len(x)
    if n == 0:
        return NAN
    if n == 1:
        return Estimate(float(x[0]), float("nan"), 1)
    return Estimate(float(x.mean()), float(t_critical(n - 1) * x.std(ddof=1) / math.sqrt(n)), n)


def points(red: Values) -> Estimate:
    return mean_ci(red)


def difference(red: Values, blue: Values) -> Estimate:
    return mean_ci(np.asarray(red, dtype=float) - np.asarray(blue, dtype=float))


def win_rate(red: Values, blue: Values) -> Estimate:
    return mean_ci(results(red, blue))


def sabotage(blue: Sequence[float], sigma_blue: float | None, sigma: Estimate | None = None) -> Estimate:
    """σ_blue − mean(S_blue). With `sigma` (σ_blue's own estimate) its uncertainty widens the interval."""
    if sigma_blue is None or (isinstance(sigma_blue, float) and math.isnan(sigma_blue)):
        return NAN
    b = mean_ci(blue)
    if b.n == 0:
        return NAN
    mean = float(sigma_blue) - b.mean
    if b.n < 2:
        return Estimate(mean, float("nan"), b.n)
    sb = np.std(np.asarray(blue, dtype=float), ddof=1) / math.sqrt(b.n)
    if sigma is None or sigma.n < 2 or math.isnan(sigma.ci):
        return Estimate(mean, t_critical(b.n - 1) * sb, b.n)
    return Estimate(mean, welch_half_width(sb, b.n, sigma.se, sigma.n), b.n)


def welch_half_width(se_a: float, n_a: int, se_b: float, n_b: int) -> float:
    """95 % half-width of a difference of two independent means from their standard errors, with
    Welch–Satterthwaite degrees of freedom (both n ≥ 2)."""
    var = se_a**2 + se_b**2
    if var == 0:
        return 0.0
    df = var**2 / ((se_a**4) / (n_a - 1) + (se_b**4) / (n_b - 1))
    return float(t_critical(df) * math.sqrt(var))


def mean_of_estimates(estimates: Sequence[Estimate]) -> Estimate:
    """The mean of independent estimates (S over all opponents); CI from their standard errors."""
    es = [e for e in estimates if not math.isnan(e.mean)]
    if not es:
        return NAN
    mean = float(np.mean([e.mean for e in es]))
    ses = [e.se for e in es]
    if any(math.isnan(s) for s in ses):
        return Estimate(mean, float("nan"), sum(e.n for e in es))
    se = math.sqrt(sum(s**2 for s in ses)) / len(es)
    df = max(1, min(e.n for e in es) - 1)  # conservative
    return Estimate(mean, t_critical(df) * se, sum(e.n for e in es))


def pairing(
    red: Sequence[float], blue: Sequence[float], sigma_blue: float | None = None, sigma: Estimate | None = None
) -> dict[str, Estimate]:
    """P, S, D, W of one pairing from the final scores of its episodes (already scaled)."""
    return {
        "P": points(red),
        "S": sabotage(blue, sigma_blue, sigma),
        "D": difference(red, blue),
        "W": win_rate(red, blue),
    }


def over_opponents(
    groups: Sequence[tuple[Sequence[float], Sequence[float], float | None, Estimate | None]],
) -> dict[str, Estimate]:
    """The "all opponents" column: groups are (red, blue, σ_blue, σ estimate) per opponent."""
    red = np.concatenate([np.asarray(g[0], dtype=float) for g in groups]) if groups else np.array([])
    blue = np.concatenate([np.asarray(g[1], dtype=float) for g in groups]) if groups else np.array([])
    return {
        "P": points(red),
        "S": mean_of_estimates([sabotage(g[1], g[2], g[3]) for g in groups]),
        "D": difference(red, blue),
        "W": win_rate(red, blue),
    }


def llm_metrics(records: Iterable[dict], original_latency: bool = True) -> dict[str, float | int | None]:
    """T_resp, N_out, R_tps (paper: mean of per-call tokens/s) over successful calls of ledger records."""
    lat, out = [], []
    for r in records:
        if r.get("error_type"):
            continue
        latency = r.get("orig_latency_s") if original_latency and r.get("cache_hit") else r.get("latency_s")
        lat.append(float(latency or 0.0))
        out.append(int(r.get("output_tokens") or 0))
    if not lat:
        return {"calls": 0, "T_resp": None, "N_out": None, "R_tps": None, "r_tps_total": None}
    lat_a, out_a = np.array(lat), np.array(out, dtype=float)
    pos = lat_a > 0
    return {
        "calls": len(lat),
        "T_resp": float(lat_a.mean()),
        "N_out": float(out_a.mean()),
        "R_tps": float((out_a[pos] / lat_a[pos]).mean()) if pos.any() else None,
        "r_tps_total": float(out_a.sum() / lat_a.sum()) if lat_a.sum() > 0 else None,
    }


def iterations(per_episode: Iterable[Sequence[int]]) -> Estimate:
    """I: per episode the mean iterations of the red team's players, then the mean over episodes."""
    return mean_ci([float(np.mean(it)) for it in per_episode if len(it)])
