"""The generalization gap: a metric on layouts a team has never seen minus the same metric on the
paper's layout (issue 29; docs/layouts.md).

Unseen layouts are those of the held-out splits (UNSEEN): `test` layouts are drawn fresh for every
episode, `dev` layouts are public seeds for tuning (unseen by the paper's map, not by a tuner). The
gap's 95 % interval is that of a difference of two independent means from their standard errors,
with Welch–Satterthwaite degrees of freedom (formulas.welch_half_width, as side symmetry's).
`unseen_arenas` is the report's section "Unseen arenas" (report/generalization.py formats it).
"""

from __future__ import annotations

import math

import pandas as pd

from pillagerbench.metrics.columns import Col
from pillagerbench.metrics.estimate import METRICS
from pillagerbench.metrics.estimates import team_estimates
from pillagerbench.metrics.formulas import NAN, Estimate, welch_half_width

UNSEEN = ("test", "dev")  # the splits of generated layouts, in the order they are reported


def gap(unseen: Estimate, paper: Estimate) -> Estimate:
    """unseen − paper, with a 95 % interval when both have one (else nan)."""
    diff = unseen.mean - paper.mean
    n = unseen.n + paper.n
    if min(unseen.n, paper.n) < 2 or math.isnan(unseen.se) or math.isnan(paper.se):
        return Estimate(diff, float("nan"), n)
    return Estimate(diff, welch_half_width(unseen.se, unseen.n, paper.se, paper.n), n)


COLUMNS = [
    "scenario",
    "team",
    "split",
    "metric",
    "paper_episodes",
    "paper",
    "paper_ci",
    "unseen_episodes",
    "unseen",
    "unseen_ci",
    "gap",
    "gap_ci",
]


def unseen_arenas(df: pd.DataFrame, sigma: dict) -> pd.DataFrame:
    """Every team's P, S, D, W on the paper's layout and on each unseen split, and the gap: one row per
    scenario, team, unseen split and metric; empty without episodes on unseen layouts. S uses the same σ
    on both arenas, so in the gap σ cancels: the gap of S is computed with σ taken as exact, and its
    interval is that of the opponents' points alone."""
    if not len(df) or Col.SPLIT not in df or not df[Col.SPLIT].isin(UNSEEN).any():
        return pd.DataFrame(columns=COLUMNS)
    exact = {k: Estimate(e.mean, math.nan, e.n) for k, e in sigma.items()}  # σ as exact: it cancels in the gap
    paper = df[df[Col.SPLIT] == "paper"]
    shown_paper, gap_paper = _estimates(paper, sigma), _estimates(paper, exact)
    rows = []
    for split in (s for s in UNSEEN if (df[Col.SPLIT] == s).any()):
        unseen = df[df[Col.SPLIT] == split]
        shown, for_gap = _estimates(unseen, sigma), _estimates(unseen, exact)
        for key, metrics in shown.items():
            before, before_gap = shown_paper.get(key), gap_paper.get(key)
            for m, e in metrics.items():
                p = before[m] if before else NAN
                g = gap(for_gap[key][m], before_gap[m]) if before_gap else NAN
                rows.append([*key, split, m, p.n, p.mean, p.ci, e.n, e.mean, e.ci, g.mean, g.ci])
    return pd.DataFrame(rows, columns=COLUMNS)


def _estimates(df: pd.DataFrame, sigma: dict) -> dict[tuple[str, str], dict[str, Estimate]]:
    """(scenario, team) -> metric -> its estimate over the team's episodes (n: all of them)."""
    return {
        key: {m: Estimate(e.metric(m).mean, e.metric(m).ci, e.episodes) for m in METRICS}
        for key, (e, _) in team_estimates(df, sigma).items()
    }
