"""The pool's view: the maximal lottery over the entrants (a game-theoretic rating that a cycle of
counters does not fool). The margin matrix M[i, j] = P(i beats j) − P(j beats i) from the games; the
maximal lottery is the mixed strategy p of the symmetric zero-sum game M that no entrant beats on
average (p·M ≥ 0 against every column), found by multiplicative weights (the average of the
iterates converges to it); an entrant's Nash-averaged margin is (M·p)_i, its expected margin against
the lottery (0 for those in its support, below 0 for the rest)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from pillagerbench.stats.bradley_terry import Game, wins_matrix


def margins(games: Sequence[Game], names: Sequence[str]) -> np.ndarray:
    wins = wins_matrix(games, names)
    games_between = wins + wins.T
    with np.errstate(invalid="ignore", divide="ignore"):
        m = np.where(games_between > 0, (wins - wins.T) / games_between, 0.0)
    return m


def maximal_lottery(m: np.ndarray, steps: int = 20000, rate: float = 0.05) -> np.ndarray:
    """The (approximate) maximal lottery of margin matrix m: a probability per entrant."""
    n = len(m)
    weights = np.zeros(n)
    total = np.zeros(n)
    for _ in range(steps):
        p = np.exp(weights - weights.max())
        p /= p.sum()
        total += p
        weights += rate * (m @ p)  # each row's payoff against the current mixture
    p = total / steps
    p[p < 1e-3] = 0.0
    return p / p.sum()


def pool_view(games: Sequence[Game], names: Sequence[str]) -> dict[str, tuple[float, float]]:
    """Each entrant's (share of the maximal lottery, Nash-averaged margin)."""
    m = margins(games, names)
    p = maximal_lottery(m)
    avg = m @ p
    return {n: (float(p[i]), float(avg[i])) for i, n in enumerate(names)}
