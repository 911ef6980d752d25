"""Differences between entrants, paired where the design allows (issue 41).

Two entrants that played the same opponent on the same side, on the same layouts with the same
episode seeds (a compare run, or series sharing their seed), met the same worlds: the difference of
their points episode by episode removes what the world gave both, so its interval is narrower than
the difference of two independent means. `difference` uses the pairs when at least two episodes
pair up (the same scenario, opponent, side, layout and seed, each once), else the two means
(Welch); each row says which design it used, and gives the unpaired interval beside it.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import pandas as pd

from pillagerbench.config.sides import SIDES, other_side
from pillagerbench.metrics.columns import Col
from pillagerbench.metrics.formulas import Estimate, mean_ci, welch_half_width

KEY = (Col.LAYOUT, Col.SEED)  # what makes two episodes the same world


@dataclass(frozen=True)
class Difference:
    estimate: Estimate  # a − b in points, with the design's interval
    unpaired: Estimate  # the same difference as two independent means
    design: str  # "paired (n pairs)" | "unpaired"


def unpaired(a: pd.Series, b: pd.Series) -> Estimate:
    ea, eb = mean_ci(a), mean_ci(b)
    if ea.n < 2 or eb.n < 2:
        return Estimate(ea.mean - eb.mean, float("nan"), min(ea.n, eb.n))
    return Estimate(ea.mean - eb.mean, welch_half_width(ea.se, ea.n, eb.se, eb.n), min(ea.n, eb.n))


def difference(a: pd.DataFrame, b: pd.DataFrame, score: str) -> Difference:
    """a's `score` minus b's over their episodes (rows with KEY columns where they were recorded)."""
    loose = unpaired(a[score], b[score])
    if not set(KEY) <= set(a.columns) & set(b.columns):
        return Difference(loose, loose, "unpaired")
    once_a, once_b = (d.drop_duplicates(list(KEY), keep=False).set_index(list(KEY))[score] for d in (a, b))
    shared = once_a.index.intersection(once_b.index)
    if len(shared) < 2:
        return Difference(loose, loose, "unpaired")
    paired = mean_ci(once_a.loc[shared].to_numpy() - once_b.loc[shared].to_numpy())
    return Difference(paired, loose, f"paired ({len(shared)} pairs)")


def differences(df: pd.DataFrame) -> pd.DataFrame:
    """Per scenario, opponent and side: every two entrants that played that opponent there, their
    points' difference (a − b), paired where the episodes pair up, the unpaired interval beside."""
    rows = []
    for (scenario, side), d in df.groupby([Col.SCENARIO, "side"], sort=False):
        for opponent, vs in d.groupby("opponent", sort=False):
            entrants = list(dict.fromkeys(vs["entrant"]))
            for x, y in itertools.combinations(entrants, 2):
                found = difference(vs[vs["entrant"] == x], vs[vs["entrant"] == y], "points")
                rows.append(
                    {
                        "scenario": scenario,
                        "opponent": opponent,
                        "side": side,
                        "a": x,
                        "b": y,
                        "a_minus_b": found.estimate.mean,
                        "a_minus_b_ci": found.estimate.ci,
                        "design": found.design,
                        "unpaired_ci": found.unpaired.ci,
                    }
                )
    return pd.DataFrame(rows, columns=COLUMNS)


COLUMNS = ["scenario", "opponent", "side", "a", "b", "a_minus_b", "a_minus_b_ci", "design", "unpaired_ci"]


def by_entrant(episodes: pd.DataFrame) -> pd.DataFrame:
    """The episodes as one row per entrant and episode (red's and blue's views): scenario, side,
    entrant, opponent, points, and the world (layout, seed) where recorded."""
    if not len(episodes):  # nothing used (every episode spoiled): no rows, the same columns
        return pd.DataFrame(columns=[Col.SCENARIO, "side", "entrant", "opponent", "points", *KEY])
    views = []
    for side, other in ((s, other_side(s)) for s in SIDES):
        view = pd.DataFrame(
            {
                Col.SCENARIO: episodes[Col.SCENARIO],
                "side": side,
                "entrant": episodes[Col.name(side)],
                "opponent": episodes[Col.name(other)],
                "points": episodes[Col.score(side)],
            }
        )
        for k in KEY:
            if k in episodes.columns:
                view[k] = episodes[k].astype(str)
        views.append(view)
    return pd.concat(views, ignore_index=True)
