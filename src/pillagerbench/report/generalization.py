"""The report's section "Unseen arenas": every team's P, S, D, W on the paper's layout and on
generated layouts of a held-out split (test, dev), each ± its 95 % interval, and the gap (unseen −
paper, metrics/generalization.py). Only runs with episodes on such layouts have it.

Each team is seen from its own side, whichever side it played (tables.per_team). S uses the same σ
(the opponent's mean points against do_nothing) on both arenas, so in the gap σ cancels: the gap of
S is computed with σ taken as exact, and its interval is that of the opponents' points alone.
"""

from __future__ import annotations

import math

import pandas as pd

from pillagerbench.metrics.columns import Col
from pillagerbench.metrics.formulas import Estimate
from pillagerbench.metrics.generalization import UNSEEN, gap
from pillagerbench.report.tables import METRICS, per_team

NAME = "unseen_arenas"
TITLE = "Unseen arenas: each team on the paper's layout and on layouts it has never met (gap = unseen − paper)"
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


def _estimates(frame: pd.DataFrame) -> dict[tuple[str, str], dict[str, Estimate]]:
    """per_team's rows as (scenario, team) -> metric -> Estimate."""
    return {
        (r["scenario"], r["team"]): {m: Estimate(r[m], r[f"{m}_ci"], int(r["episodes"])) for m in METRICS}
        for _, r in frame.iterrows()
    }


def unseen_arenas(df: pd.DataFrame, sigma: dict) -> pd.DataFrame:
    """One row per scenario, team, unseen split and metric; empty without episodes on unseen layouts."""
    if not len(df) or Col.SPLIT not in df or not df[Col.SPLIT].isin(UNSEEN).any():
        return pd.DataFrame(columns=COLUMNS)
    exact = {k: Estimate(e.mean, math.nan, e.n) for k, e in sigma.items()}  # σ as exact: it cancels in the gap
    paper = df[df[Col.SPLIT] == "paper"]
    shown_paper, gap_paper = _estimates(per_team(paper, sigma)), _estimates(per_team(paper, exact))
    rows = []
    for split in (s for s in UNSEEN if (df[Col.SPLIT] == s).any()):
        unseen = df[df[Col.SPLIT] == split]
        shown, for_gap = _estimates(per_team(unseen, sigma)), _estimates(per_team(unseen, exact))
        for key, metrics in shown.items():
            before, before_gap = shown_paper.get(key), gap_paper.get(key)
            for m, e in metrics.items():
                p = before[m] if before else Estimate(math.nan, math.nan, 0)
                g = gap(for_gap[key][m], before_gap[m]) if before_gap else Estimate(math.nan, math.nan, 0)
                rows.append([*key, split, m, p.n, p.mean, p.ci, e.n, e.mean, e.ci, g.mean, g.ci])
    return pd.DataFrame(rows, columns=COLUMNS)


def unseen_notes(df: pd.DataFrame) -> list[str]:
    """What the section rests on and how to read it (nothing without unseen layouts)."""
    if not len(df) or Col.SPLIT not in df or not df[Col.SPLIT].isin(UNSEEN).any():
        return []
    counts = ", ".join(
        f"{int((df[Col.SPLIT] == s).sum())} on {df.loc[df[Col.SPLIT] == s, Col.LAYOUT].nunique()} {s} layout(s)"
        for s in UNSEEN
        if (df[Col.SPLIT] == s).any()
    )
    return [
        f"unseen arenas: {counts}, {int((df[Col.SPLIT] == 'paper').sum())} on the paper's layout; gap = unseen − "
        "paper, its 95 % interval Welch's (normal approximation, Welch–Satterthwaite df) from the two standard "
        "errors; the other tables pool every layout"
    ]
