"""The board to arena standards (issue 41): Bradley–Terry ratings with bootstrap 95 % intervals as the
headline beside OpenSkill's, the pool's view (each entrant's share of the maximal lottery and its
Nash-averaged margin, so that a cycle of counters does not decide the order), cost per win, and a
plot of rating against dollars per episode. Games are the league's episodes: the higher final score
wins, equal scores draw; the BT scale is Elo's, do_nothing at 0 (stats/bradley_terry.py)."""

from __future__ import annotations

import math
from pathlib import Path

import pandas as pd

from pillagerbench.league.ratings import ANCHOR, Outcome
from pillagerbench.stats.bradley_terry import Game, rate
from pillagerbench.stats.lottery import pool_view
from pillagerbench.stats.result import result

COLUMNS = ("BT rating", "BT 95% low", "BT 95% high", "lottery share", "Nash margin", "LLM cost/win")
BOOTSTRAP_ROUNDS = 500


def games_of(outs: list[Outcome]) -> list[Game]:
    """One game per episode between two different entrants: red's result 1, 0.5 or 0."""
    return [
        (o.red, o.blue, result(o.red_score, o.blue_score))
        for o in sorted(outs, key=lambda o: o.order)
        if o.red != o.blue
    ]


def arena_columns(outs: list[Outcome], names: list[str], spend: pd.DataFrame) -> dict[str, dict[str, float]]:
    """Each entrant's columns of COLUMNS (NaN where it has no games, or no priced calls or wins)."""
    games = [g for g in games_of(outs) if g[0] in names and g[1] in names]
    bt = rate(games, names, anchor=ANCHOR, rounds=BOOTSTRAP_ROUNDS)
    pool = pool_view(games, names)
    out = {}
    for n in names:
        wins = sum((a == n and r == 1) or (b == n and r == 0) for a, b, r in games)
        calls = spend[spend["entrant"] == n]
        priced = len(calls) and not calls["cost"].isna().any()
        cost = float(calls["cost"].astype(float).sum()) if priced else math.nan
        played = bt[n].games > 0
        out[n] = {
            "BT rating": bt[n].rating if played else math.nan,
            "BT 95% low": bt[n].low if played else math.nan,
            "BT 95% high": bt[n].high if played else math.nan,
            "lottery share": pool[n][0] if played else math.nan,
            "Nash margin": pool[n][1] if played else math.nan,
            "LLM cost/win": cost / wins if wins and not math.isnan(cost) else math.nan,
        }
    return out


def cost_plot(board: pd.DataFrame, out: Path) -> Path | None:
    """BT rating (with its interval) against LLM dollars per episode, for the entrants with a known
    cost; None when fewer than one has both."""
    rows = board.dropna(subset=["BT rating", "LLM cost/episode"])
    if not len(rows):
        return None
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4))
    low = rows["BT rating"] - rows["BT 95% low"]
    high = rows["BT 95% high"] - rows["BT rating"]
    ax.errorbar(rows["LLM cost/episode"], rows["BT rating"], yerr=[low, high], fmt="o", capsize=3)
    for _, r in rows.iterrows():
        ax.annotate(
            str(r["entrant"]), (r["LLM cost/episode"], r["BT rating"]), textcoords="offset points", xytext=(4, 4)
        )
    ax.set_xlabel("LLM cost per episode (USD)")
    ax.set_ylabel("Bradley–Terry rating (do_nothing = 0)")
    ax.set_title("Rating against dollars")
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    plt.close(fig)
    return out
