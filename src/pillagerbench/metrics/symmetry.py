"""Side symmetry: does the side a team plays decide its score?

For every pairing of two teams that met in a scenario, each team's final points as red (against
the other as blue) are compared with its points as blue (against the other as red); a team against
itself (a mirror match) compares the red and the blue team of the same episodes. The difference
red − blue gets a Welch 95 % interval; "no side effect" (✓) means the interval contains 0.
Pairings played in one order only are listed, not compared. Dash & Dine points are ×0.1.

`pillagerbench symmetry RUN_DIR...` prints the table (report/symmetry.py); `pillagerbench report`
has it as a section.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from pillagerbench.metrics.columns import Col
from pillagerbench.metrics.formulas import NAN, Estimate, mean_ci, welch_half_width

COLUMNS = [
    "scenario",
    "team",
    "opponent",
    "n_red",
    "as_red",
    "as_red_ci",
    "n_blue",
    "as_blue",
    "as_blue_ci",
    "red_minus_blue",
    "red_minus_blue_ci",
    "no_side_effect",
]


def welch(a, b) -> Estimate:
    """Mean of a − mean of b with a Welch 95 % interval (nan with < 2 values a side)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    diff = float(a.mean() - b.mean()) if len(a) and len(b) else float("nan")
    if len(a) < 2 or len(b) < 2:
        return Estimate(diff, float("nan"), len(a) + len(b))
    se_a, se_b = a.std(ddof=1) / math.sqrt(len(a)), b.std(ddof=1) / math.sqrt(len(b))
    return Estimate(diff, welch_half_width(se_a, len(a), se_b, len(b)), len(a) + len(b))


def verdict(diff: Estimate) -> str:
    if math.isnan(diff.ci):
        return "–"
    return "✓" if abs(diff.mean) <= diff.ci else "✗"


def pairs_of(df: pd.DataFrame) -> list[tuple[str, str, str]]:
    """(scenario, a, b) for every pairing that met, in order of appearance, each once."""
    seen: dict[tuple, None] = {}
    for sc, red, blue in zip(df[Col.SCENARIO], df[Col.RED], df[Col.BLUE]):
        seen.setdefault((sc, *sorted((red, blue))), None)
    return list(seen)


def side_symmetry(df: pd.DataFrame) -> tuple[pd.DataFrame, list[str]]:
    """The table (one row per team and pairing) and notes on what could not be compared."""
    rows, notes = [], []
    if not len(df):
        return pd.DataFrame(columns=COLUMNS), ["side symmetry: no finished episodes"]
    for sc, a, b in pairs_of(df):
        one = df[(df[Col.SCENARIO] == sc) & (df[Col.RED] == a) & (df[Col.BLUE] == b)]
        other = df[(df[Col.SCENARIO] == sc) & (df[Col.RED] == b) & (df[Col.BLUE] == a)]
        if a != b and (not len(one) or not len(other)):
            red, blue = (a, b) if len(one) else (b, a)
            notes.append(
                f"side symmetry: {sc} {a} vs {b} was played in one order only ({red} red, {blue} blue); "
                f"play {blue} red vs {red} blue too to compare sides"
            )
        teams = [(a, b, one, other)] if a == b else [(a, b, one, other), (b, a, other, one)]
        for team, opp, team_red, team_blue in teams:
            red_pts = team_red[Col.RED_SCORE].to_numpy()
            blue_pts = team_blue[Col.BLUE_SCORE].to_numpy()
            r, bl = (mean_ci(red_pts) if len(red_pts) else NAN), (mean_ci(blue_pts) if len(blue_pts) else NAN)
            diff = welch(red_pts, blue_pts)
            if len(red_pts) and len(blue_pts) and math.isnan(diff.ci):
                notes.append(
                    f"side symmetry: {sc} {team} vs {opp}: too few episodes for an interval "
                    f"({len(red_pts)} as red, {len(blue_pts)} as blue; 2 each at least)"
                )
            rows.append(
                {
                    "scenario": sc,
                    "team": team,
                    "opponent": opp,
                    "n_red": len(red_pts),
                    "as_red": r.mean,
                    "as_red_ci": r.ci,
                    "n_blue": len(blue_pts),
                    "as_blue": bl.mean,
                    "as_blue_ci": bl.ci,
                    "red_minus_blue": diff.mean,
                    "red_minus_blue_ci": diff.ci,
                    "no_side_effect": verdict(diff),
                }
            )
    return pd.DataFrame(rows, columns=COLUMNS), notes
