"""Fidelity: do our built-in opponents score what upstream's scored, and do the paper's Benchmark
Analysis claims hold on our runs?

1. Against do_nothing (experiment=fidelity, or the do_nothing rows of a calibration or round robin):
   per opponent and side its mean points ± 95 % interval, upstream's reference value, the ratio and
   ✓ when the ratio is within ±25 % (REFERENCE_SCORES, Dash & Dine ×0.1 like every reported score);
   beside it the suite's own reference (suite/reference_figures.json) and ✓ in `vs_suite` when the two
   means differ by no more than their combined 95 % intervals (sqrt(ci² + ci_ref²)).
   Episodes that recorded both scorings (scoring=upstream) give a row per scoring.
2. From a round robin (experiment=round_robin_mushroom_war / round_robin_dash_and_dine): each
   claim of CLAIMS with the numbers behind it and ✓/✗. A claim is data: a kind (one checking
   function of CHECKS) and its arguments; the per-team numbers are the red team's over all
   opponents (the paper's heatmaps' "all opponents" column) and, for timing, the time to its
   first points.

`pillagerbench fidelity RUN_DIR...` prints both (report/fidelity.py); `pillagerbench report` has
them as sections. What cannot be checked (no do_nothing episodes, too few episodes, a scenario
without references, a team missing from the round robin) is one note each; the rest is printed.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from pillagerbench.config.sides import other_side
from pillagerbench.experiments.spec import builtin_teams
from pillagerbench.match import SCORINGS
from pillagerbench.metrics.calibration import FROM_RUNS, against_do_nothing, opponent_groups
from pillagerbench.metrics.columns import Col
from pillagerbench.metrics.formulas import Estimate, mean_ci, over_opponents, welch_half_width
from pillagerbench.metrics.reference import (
    REFERENCE_CONDITIONS,
    REFERENCE_LENGTH,
    REFERENCE_SCORES,
    REFERENCE_SPLIT,
)
from pillagerbench.metrics.runs import Runs
from pillagerbench.suite.conditions import describe, suite_defaults
from pillagerbench.suite.figures import reference_figures

TOLERANCE = 0.25  # ✓ when mean / reference is within 1 ± TOLERANCE
MIN_EPISODES = 10  # per opponent and side (the fidelity check's default)
MIN_PAIRING_EPISODES = 3  # per round-robin pairing for the claims

FIDELITY_COLUMNS = [
    "scenario",
    "opponent",
    "side",
    "scoring",
    "episodes",
    "points",
    "points_ci",
    "do_nothing",
    "do_nothing_ci",
    "reference",
    "ratio",
    "within_25pct",
    "suite_reference",
    "suite_reference_ci",
    "vs_suite",
    "conditions",
]
CLAIM_COLUMNS = ["scenario", "claim", "evidence", "holds"]


def fidelity_table(df: pd.DataFrame) -> tuple[pd.DataFrame, list[str]]:
    """Per opponent, side and scoring: its points against do_nothing beside upstream's reference."""
    rows, notes = [], []
    few: list[str] = []
    unlike: dict[str, list[str]] = {}  # conditions unlike the references' -> the rows played under them
    for side in ("blue", "red"):
        other = other_side(side)
        for scenario, team, g in against_do_nothing(df, side):
            if team == "do_nothing" or (scenario in REFERENCE_SCORES and team not in builtin_teams(scenario)):
                continue  # the check is about the built-in opponents (an LLM team's row is the report's)
            differ = unlike_references(g)
            if differ:
                unlike.setdefault(differ, []).append(f"{scenario} {team} ({side})")
            reference = None if differ else REFERENCE_SCORES.get(scenario, {}).get(team)
            for scoring in SCORINGS:
                mine, theirs = g[Col.by_scoring(side, scoring)].dropna(), g[Col.by_scoring(other, scoring)].dropna()
                if not len(mine):
                    continue
                e, dn = mean_ci(mine), mean_ci(theirs)
                ratio = e.mean / reference if reference else math.nan
                rows.append(
                    {
                        "scenario": scenario,
                        "opponent": team,
                        "side": side,
                        "scoring": scoring,
                        "episodes": e.n,
                        "points": e.mean,
                        "points_ci": e.ci,
                        "do_nothing": dn.mean,
                        "do_nothing_ci": dn.ci,
                        "reference": reference if reference is not None else math.nan,
                        "ratio": ratio,
                        "within_25pct": "–" if math.isnan(ratio) else "✓" if abs(ratio - 1) <= TOLERANCE else "✗",
                        **(NO_SUITE_FIGURE if differ else beside_suite(scenario, team, scoring, e)),
                        "conditions": played_under(g),
                    }
                )
                if e.n < MIN_EPISODES and f"{scenario} {team} ({side}): {e.n}" not in few:  # once, not per scoring
                    few.append(f"{scenario} {team} ({side}): {e.n}")
    if not rows:
        notes.append(
            "fidelity: no built-in opponent played against do_nothing in these runs, so no table against upstream's references "
            "(play experiment=fidelity)"
        )
    if few:
        notes.append(
            f"fidelity: too few episodes for the check (≥ {MIN_EPISODES} per opponent and side): "
            + ", ".join(few[:5])
            + (f" and {len(few) - 5} more" if len(few) > 5 else "")
        )
    notes += [
        f"fidelity: no reference for these conditions ({differ}): {', '.join(where)}; the references are "
        f"{REFERENCE_LENGTH:g} s episodes with {describe(REFERENCE_CONDITIONS)} on the {REFERENCE_SPLIT}'s layout "
        "(paper=true)"
        for differ, where in unlike.items()
    ]
    table = pd.DataFrame(rows, columns=FIDELITY_COLUMNS)
    if len(table) and table["suite_reference"].notna().any():
        figures = reference_figures()
        notes.append(
            f"fidelity: vs_suite compares with {figures.suite}'s own reference (suite/reference_figures.json; "
            f"{figures.status.split(':')[0]})"
        )
    unknown = sorted(set(table["scenario"]) - set(REFERENCE_SCORES)) if len(table) else []
    if unknown:
        notes.append(
            f"fidelity: no reference values for {', '.join(unknown)} (upstream measured "
            f"{', '.join(REFERENCE_SCORES)} only): listed without a ratio"
        )
    return table, notes


def _rules(g: pd.DataFrame) -> set[str]:
    """The rules each episode was played under besides its scoring (both scorings are columns)."""
    return {describe({k: v for k, v in c.items() if k != "scoring"}) for c in g["conditions"]}


def played_under(g: pd.DataFrame) -> str:
    """The rules of the episodes besides their scoring ('' for the suite's defaults), `; `-joined."""
    return "; ".join(sorted(_rules(g)))


# besides the rules the references were played under, what they still apply to: either scoring (both
# are columns), and either clock (lockstep is the same game on another clock: this table checks that;
# the conditions column says which clock played)
SAME_GAME = frozenset({"scoring", "clock.mode"})


def unlike_references(g: pd.DataFrame) -> str:
    """'' when every episode was played as the references were (rules, length, split), else what
    differs, as `key=value` of the episodes."""
    differ: list[str] = []
    for scenario, conditions in zip(g["scenario"], g["conditions"]):
        defaults = suite_defaults(scenario)
        for key in sorted((set(conditions) | set(REFERENCE_CONDITIONS)) - SAME_GAME):
            mine = conditions.get(key, defaults.get(key))
            if key != "episode_length" and mine != REFERENCE_CONDITIONS.get(key, defaults.get(key)):
                differ.append(f"{key}={mine}")
    differ += [f"episode_length={L:g}" for L in sorted(set(g["episode_length"])) if L != REFERENCE_LENGTH]
    differ += [f"split={s}" for s in sorted(set(g["split"])) if s != REFERENCE_SPLIT]
    return ", ".join(dict.fromkeys(differ))


NO_SUITE_FIGURE = {"suite_reference": math.nan, "suite_reference_ci": math.nan, "vs_suite": "–"}


def beside_suite(scenario: str, team: str, scoring: str, e) -> dict:
    """The suite's own figure for this opponent and scoring, and ✓ when the run's mean agrees with
    it within the two intervals combined (– without a figure or an interval)."""
    ref = reference_figures().of(scenario, team, scoring)
    if ref is None:
        return NO_SUITE_FIGURE
    spread = math.hypot(e.ci, ref.ci)
    mark = "–" if math.isnan(spread) else "✓" if abs(e.mean - ref.mean) <= spread else "✗"
    return {"suite_reference": ref.mean, "suite_reference_ci": ref.ci, "vs_suite": mark}


# -- the paper's Benchmark Analysis claims ------------------------------------------------------------
@dataclass(frozen=True)
class Claim:
    scenario: str
    text: str
    kind: str  # a key of CHECKS
    args: dict = field(default_factory=dict)


CLAIMS: tuple[Claim, ...] = (
    Claim("mushroom_war", "passive has the highest points", "highest", {"team": "passive", "metrics": ["P"]}),
    Claim(
        "mushroom_war",
        "slimy is close to passive in win rate (within 0.1, or no significant difference at 95 %)",
        "close",
        {"team": "slimy", "other": "passive", "metric": "W", "within": 0.1},
    ),
    Claim(
        "mushroom_war",
        "each mushroom breaker (aggressive, balanced) scores higher in sabotage and lower in points than "
        "each of the others (passive, slimy)",
        "contrast",
        {"group": ["aggressive", "balanced"], "others": ["passive", "slimy"], "higher": ["S"], "lower": ["P"]},
    ),
    Claim(
        "mushroom_war",
        "do_nothing gets non-zero points and a negative sabotage score",
        "signs",
        {"team": "do_nothing", "positive": ["P"], "negative": ["S"]},
    ),
    Claim(
        "dash_and_dine",
        "berries leads in points, sabotage and win rate",
        "highest",
        {"team": "berries", "metrics": ["P", "S", "W"]},
    ),
    Claim(
        "dash_and_dine",
        "berries loses only to potato_cookie (win rate < 0.5 as red)",
        "loses_only_to",
        {"team": "berries", "winners": ["potato_cookie"]},
    ),
    Claim(
        "dash_and_dine",
        "the time to the first points is longer than in Mushroom War",
        "later_than",
        {"other_scenario": "mushroom_war"},
    ),
    Claim(
        "dash_and_dine",
        "the cake, beetroot soup and baked potato builders (cake_beetroot, potato_cookie) take longest to "
        "their first points",
        "contrast",
        {"group": ["cake_beetroot", "potato_cookie"], "others": ["berries", "melon_pumpkin"], "higher": ["T1"]},
    ),
)


def first_points(t: np.ndarray, red_t: np.ndarray, length: float) -> float:
    """Seconds until the red team's score first rises above 0 (the episode length if it never does)."""
    hit = np.nonzero(np.asarray(red_t) > 0)[0]
    return float(np.asarray(t)[hit[0]]) if len(hit) else float(length)


Stats = dict[str, dict[str, Estimate]]  # team -> metric -> estimate (P, S, W, T1)


def _num(e: Estimate) -> str:
    return e.fmt()


def _check_highest(stats: Stats, a: dict, ctx: dict) -> tuple[str, str]:
    """`team` strictly above every other team in each of `metrics` (a tie is not a lead)."""
    team, ok, evidence = a["team"], True, []
    for m in a["metrics"]:
        if math.isnan(stats[team][m].mean):
            raise _Missing(f"no {m} for {team}" + (" (no σ_blue: pillagerbench calibrate)" if m == "S" else ""))
        ranked = sorted(stats, key=lambda t: -stats[t][m].mean if not math.isnan(stats[t][m].mean) else math.inf)
        runner = next((t for t in ranked if t != team), None)
        ok &= runner is None or math.isnan(stats[runner][m].mean) or stats[team][m].mean > stats[runner][m].mean
        evidence.append(
            f"{m}: {team} {_num(stats[team][m])}" + (f", next {runner} {_num(stats[runner][m])}" if runner else "")
        )
    return ("✓" if ok else "✗"), "; ".join(evidence)


def _check_close(stats: Stats, a: dict, ctx: dict) -> tuple[str, str]:
    x, y = stats[a["team"]][a["metric"]], stats[a["other"]][a["metric"]]
    diff = x.mean - y.mean
    half = welch_half_width(x.se, x.n, y.se, y.n) if x.n > 1 and y.n > 1 and not math.isnan(x.se + y.se) else math.nan
    ok = abs(diff) <= a["within"] + 1e-9 or (not math.isnan(half) and abs(diff) <= half)
    return ("✓" if ok else "✗"), (
        f"{a['metric']}: {a['team']} {_num(x)}, {a['other']} {_num(y)}; difference {diff:+.2f}"
        + ("" if math.isnan(half) else f" ± {half:.2f}")
    )


def _group_mean(stats: Stats, teams: list[str], m: str) -> float:
    return float(np.mean([stats[t][m].mean for t in teams]))


def _check_contrast(stats: Stats, a: dict, ctx: dict) -> tuple[str, str]:
    """Every team of `group` above (`higher`) or below (`lower`) every team of `others`."""
    ok, evidence = True, []
    for m, sign in [(m, 1) for m in a.get("higher", [])] + [(m, -1) for m in a.get("lower", [])]:
        g = [stats[t][m].mean * sign for t in a["group"]]
        o = [stats[t][m].mean * sign for t in a["others"]]
        ok &= min(g) > max(o)
        group, others = (", ".join(f"{t} {stats[t][m].mean:.2f}" for t in a[k]) for k in ("group", "others"))
        evidence.append(f"{m}: {group} {'>' if sign > 0 else '<'} {others}")
    return ("✓" if ok else "✗"), "; ".join(evidence)


def _check_signs(stats: Stats, a: dict, ctx: dict) -> tuple[str, str]:
    s = stats[a["team"]]
    ok = all(s[m].mean > 0 for m in a.get("positive", [])) and all(s[m].mean < 0 for m in a.get("negative", []))
    return ("✓" if ok else "✗"), "; ".join(f"{m}: {a['team']} {_num(s[m])}" for m in a["positive"] + a["negative"])


def _check_loses_only_to(stats: Stats, a: dict, ctx: dict) -> tuple[str, str]:
    team, pair = a["team"], ctx["pairs"]
    w = {blue: e for (red, blue), e in pair.items() if red == team and blue != team}
    lost = sorted(b for b, e in w.items() if e.mean < 0.5)
    ok = lost == sorted(a["winners"])
    return ("✓" if ok else "✗"), f"win rate of {team} as red: " + ", ".join(f"{b} {_num(e)}" for b, e in w.items())


def _check_later_than(stats: Stats, a: dict, ctx: dict) -> tuple[str, str]:
    here = _group_mean(stats, list(stats), "T1")
    there_stats = ctx["all"].get(a["other_scenario"])
    if not there_stats:
        raise _Missing(f"no {a['other_scenario']} round robin among these runs")
    there = _group_mean(there_stats, list(there_stats), "T1")
    ok = here > there
    return ("✓" if ok else "✗"), (
        f"mean time to first points (non-do_nothing teams as red): {here:.1f} s here, "
        f"{there:.1f} s in {a['other_scenario']}"
    )


CHECKS: dict[str, Callable[[Stats, dict, dict], tuple[str, str]]] = {
    "highest": _check_highest,
    "close": _check_close,
    "contrast": _check_contrast,
    "signs": _check_signs,
    "loses_only_to": _check_loses_only_to,
    "later_than": _check_later_than,
}


class _Missing(Exception):
    """A claim that cannot be checked on these runs (the message says why)."""


def _teams_named(a: dict) -> list[str]:
    names = [a.get("team"), a.get("other")] + list(a.get("group", [])) + list(a.get("others", []))
    names += list(a.get("winners", []))
    return [n for n in names if n]


def _stats_of(df: pd.DataFrame, sigma: dict) -> dict[str, Stats]:
    """Per scenario: per red entrant (a built-in team is its name), P S W (over all opponents) and T1 (time to first points) estimates.
    do_nothing is left out of T1 comparisons (it never acts)."""
    out: dict[str, Stats] = {}
    main = df[df["group"].isna()] if len(df) else df
    if not len(main):
        return out
    for (scenario, red), g in main.groupby(["scenario", "red"], sort=False):
        est = over_opponents(opponent_groups(g, sigma))
        t1 = mean_ci([first_points(r.t, r.red_t, r.episode_length) for r in g.itertuples()])
        out.setdefault(scenario, {})[red] = {**est, "T1": t1}
    return out


def _round_robins(df: pd.DataFrame) -> list[str]:
    """Scenarios where built-in opponents (not do_nothing) met each other in at least two pairings."""
    out = []
    for scenario, g in df.groupby("scenario", sort=False):
        teams = set(builtin_teams(scenario)) - {"do_nothing"}
        met = {(r, b) for r, b in zip(g["red"], g["blue"]) if r in teams and b in teams}
        if len(met) >= 2:
            out.append(scenario)
    return out


def claims_table(df: pd.DataFrame, sigma: dict) -> tuple[pd.DataFrame, list[str]]:
    """Each claim of a scenario present in df, with its evidence and ✓/✗ ("–" when it cannot be checked)."""
    notes: list[str] = []
    main = df[df["group"].isna()] if len(df) else df
    main = main[main["scenario"].isin(_round_robins(main))] if len(main) else main
    if not len(main):
        notes.append(
            "claims: no round robin of the built-in opponents among these runs, so the paper's claims are not "
            "checked (experiment=round_robin_mushroom_war, round_robin_dash_and_dine)"
        )
        return pd.DataFrame(columns=CLAIM_COLUMNS), notes
    stats = _stats_of(main, sigma)
    few = []
    pairs: dict[str, dict] = {}
    for (scenario, red, blue), g in main.groupby(["scenario", "red", "blue"], sort=False) if len(main) else []:
        pairs.setdefault(scenario, {})[(red, blue)] = mean_ci(
            np.asarray(g["red_score"] > g["blue_score"], dtype=float) + 0.5 * (g["red_score"] == g["blue_score"])
        )
        if len(g) < MIN_PAIRING_EPISODES:
            few.append(f"{scenario} {red} vs {blue}: {len(g)}")
    if few:
        notes.append(
            f"claims: too few episodes per pairing (≥ {MIN_PAIRING_EPISODES} for the claims): "
            + ", ".join(few[:5])
            + (f" and {len(few) - 5} more" if len(few) > 5 else "")
        )
    rows = []
    timing = {sc: {t: s for t, s in st.items() if t != "do_nothing"} for sc, st in stats.items()}
    for c in CLAIMS:
        if c.scenario not in stats:
            continue
        st = timing[c.scenario] if c.kind in ("later_than",) or "T1" in c.args.get("higher", []) else stats[c.scenario]
        missing = [t for t in _teams_named(c.args) if t not in stats[c.scenario]]
        try:
            if missing:
                raise _Missing(f"not in these runs as red: {', '.join(missing)}")
            holds, evidence = CHECKS[c.kind](
                st, c.args, {"pairs": pairs.get(c.scenario, {}), "all": {k: v for k, v in timing.items() if v}}
            )
        except _Missing as why:
            holds, evidence = "–", str(why)
            notes.append(f"claims: {c.scenario}: cannot check “{c.text}”: {why}")
        rows.append({"scenario": c.scenario, "claim": c.text, "evidence": evidence, "holds": holds})
    if stats and not rows:
        notes.append(
            f"claims: none for {', '.join(stats)} (the paper's claims are about {', '.join(sorted({c.scenario for c in CLAIMS}))})"
        )
    return pd.DataFrame(rows, columns=CLAIM_COLUMNS), notes


SIGMA_FROM_RUNS_NOTE = (
    "claims: σ_blue comes from do_nothing-red episodes among these runs, which makes do_nothing's sabotage 0 "
    "(exactly, when they are the round robin's own); --calibration reference uses upstream's reference "
    "scores, as its analysis did"
)


def fidelity_sections(
    runs: Runs, sigma: dict, origin: dict | None = None
) -> tuple[pd.DataFrame, pd.DataFrame, list[str]]:
    """The fidelity table, the claims table and one note per thing that could not be checked or that
    a reader needs to weigh them (`origin`: where each σ came from, as calibration.resolve fills it)."""
    table, notes = fidelity_table(runs.episodes)
    claims, more = claims_table(runs.episodes, sigma)
    notes += more
    if len(claims) and any(where == FROM_RUNS and team != "do_nothing" for (_, team), where in (origin or {}).items()):
        notes.append(SIGMA_FROM_RUNS_NOTE)
    return table, claims, notes
