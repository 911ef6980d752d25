"""The ratings of a league: one board per scenario (the entrants that can play it) and overall."""

from __future__ import annotations

from pillagerbench.league.compose import playable
from pillagerbench.league.ratings import Outcome, Rating, rate
from pillagerbench.league.spec import League


def boards(league: League, outs: list[Outcome]) -> dict[str, dict[str, Rating]]:
    out = {}
    for sc in league.scenarios:
        names = [e.name for e in league.entrants if playable(e, [sc])]
        out[sc] = rate([o for o in outs if o.scenario == sc], names, league.margin)
    return out


def overall(league: League, outs: list[Outcome]) -> dict[str, Rating]:
    chosen = set(league.scenarios)
    return rate([o for o in outs if o.scenario in chosen], [e.name for e in league.entrants], league.margin)
