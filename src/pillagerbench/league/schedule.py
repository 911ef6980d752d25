"""Which matches to play next, and when a league is done.

On each scenario's board (entrants ordered by rating) an adjacent pair is *separated* when
P(upper > lower) >= confidence. The open (unseparated) adjacent pairs are the candidates; the
ones whose result would most reduce the ranking's uncertainty go first: priority = variance of
the rating difference (σ_a² + σ_b²) × overlap (1 − |2·P − 1|, 1 when the order is a coin toss).
A round takes the highest-priority pairs, an entrant in at most one match per round while other
pairs remain. A league is done when no scenario has an open adjacent pair. An entrant added to a
settled board sits between two separated entrants, so only its own pairs are open.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass

from pillagerbench.league.ratings import Outcome, Rating, p_above, ranked


@dataclass(frozen=True)
class Pairing:
    scenario: str
    red: str
    blue: str


def open_pairs(ratings: dict[str, Rating], confidence: float) -> list[tuple[float, str, str]]:
    """(priority, upper, lower) of each adjacent pair that is not yet separated."""
    order = ranked(ratings)
    out = []
    for upper, lower in zip(order, order[1:]):
        a, b = ratings[upper], ratings[lower]
        p = p_above(a, b)
        if p < confidence:
            out.append(((1 - abs(2 * p - 1)) * (a.sigma**2 + b.sigma**2), upper, lower))
    return out


def _sides(scenario: str, a: str, b: str, reds: Counter) -> Pairing:
    """The one that played red less often in this pairing plays red (ties: by name)."""
    first, second = sorted((a, b))
    if reds[(scenario, second, first)] < reds[(scenario, first, second)]:
        first, second = second, first
    return Pairing(scenario, first, second)


def next_round(
    boards: dict[str, dict[str, Rating]], outcomes: Iterable[Outcome], confidence: float, matches: int
) -> list[Pairing]:
    """Up to `matches` pairings to play next (empty when every board is separated)."""
    reds = Counter((o.scenario, o.red, o.blue) for o in outcomes)
    candidates = sorted(
        ((-prio, i, sc, a, b) for i, sc in enumerate(boards) for prio, a, b in open_pairs(boards[sc], confidence)),
    )
    chosen: list[tuple] = []
    busy: set[tuple[str, str]] = set()
    for c in candidates:  # first pass: each entrant once per scenario and round
        if len(chosen) < matches and not busy & {(c[2], c[3]), (c[2], c[4])}:
            chosen.append(c)
            busy |= {(c[2], c[3]), (c[2], c[4])}
    for c in candidates:  # then fill with the rest
        if len(chosen) < matches and c not in chosen:
            chosen.append(c)
    return [_sides(sc, a, b, reds) for _, _, sc, a, b in chosen]


def settled(boards: dict[str, dict[str, Rating]], confidence: float) -> bool:
    return not any(open_pairs(r, confidence) for r in boards.values())
