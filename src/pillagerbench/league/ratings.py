"""Ratings from episode outcomes with openskill (Plackett–Luce), per scenario and overall.

Each finished episode is one two-team game: the higher final score wins, equal scores draw
(with `margin` > 0 openskill also weighs the points difference). Episodes are rated in a fixed
order (round, series, episode), so the same episodes always give the same board. The scale is
anchored at do_nothing: every mu is shifted so that do_nothing's is 0.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from statistics import NormalDist

from openskill.models import PlackettLuce

ANCHOR = "do_nothing"


@dataclass(frozen=True)
class Outcome:
    scenario: str
    red: str  # entrant names
    blue: str
    red_score: float
    blue_score: float
    order: tuple = ()  # sort key: (round, series, episode)


@dataclass(frozen=True)
class Rating:
    mu: float
    sigma: float
    episodes: int

    @property
    def conservative(self) -> float:
        return self.mu - 3 * self.sigma

    def interval(self, confidence: float) -> float:
        """Half-width of the two-sided interval of mu at this confidence."""
        return z(confidence) * self.sigma


def z(confidence: float) -> float:
    return NormalDist().inv_cdf((1 + confidence) / 2)


def rate(outcomes: Iterable[Outcome], entrants: Iterable[str], margin: float = 0.0) -> dict[str, Rating]:
    """Every entrant's rating after the outcomes (an entrant without episodes keeps the prior)."""
    model = PlackettLuce(margin=margin)
    state = {name: model.rating(name=name) for name in entrants}
    count = dict.fromkeys(state, 0)
    for o in sorted(outcomes, key=lambda o: o.order):
        if o.red not in state or o.blue not in state or o.red == o.blue:
            continue  # an entrant no longer in the league, or a mirror match (no information)
        [[r], [b]] = model.rate([[state[o.red]], [state[o.blue]]], scores=[o.red_score, o.blue_score])
        state[o.red], state[o.blue] = r, b
        count[o.red] += 1
        count[o.blue] += 1
    shift = state[ANCHOR].mu if ANCHOR in state else 0.0
    return {n: Rating(mu=s.mu - shift, sigma=s.sigma, episodes=count[n]) for n, s in state.items()}


def p_above(a: Rating, b: Rating) -> float:
    """P(a's true rating > b's) given both ratings' uncertainty."""
    spread = math.hypot(a.sigma, b.sigma)
    return NormalDist().cdf((a.mu - b.mu) / spread) if spread else float(a.mu > b.mu)


def ranked(ratings: dict[str, Rating]) -> list[str]:
    """Names from the highest rating down (ties by name)."""
    return sorted(ratings, key=lambda n: (-ratings[n].mu, n))


def ranks(ratings: dict[str, Rating]) -> dict[str, int]:
    """Each name's place on the board: equal ratings share one (1, 1, 3), as before any episode."""
    return {n: 1 + sum(r.mu > ratings[n].mu + 1e-9 for r in ratings.values()) for n in ratings}
