"""Bradley–Terry ratings with bootstrap 95 % intervals, as arena leaderboards publish them.

P(i beats j) = s_i / (s_i + s_j). The strengths are the maximum of the likelihood (Newton's method) of a
matrix of wins (a draw counts half to each side), each entrant also given one virtual drawn game
against a reference of strength 1 (a weak prior that keeps an entrant who always won or always lost
finite). Ratings are on the Elo scale, 400 · log10(s), shifted so that the anchor (do_nothing, when
present) is 0, else their mean. The interval: percentiles of the ratings refitted on games resampled
with replacement (a fixed seed, so the same games give the same board). No maintained Python package
fits without pulling in SciPy (choix needs it; openskill is a different, online model), and the fit
is twenty lines of numpy.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

Game = tuple[str, str, float]  # (a, b, a's result: 1 won, 0.5 drew, 0 lost)


@dataclass(frozen=True)
class BTRating:
    rating: float
    low: float  # the bootstrap interval's ends
    high: float
    games: int


def wins_matrix(games: Sequence[Game], names: Sequence[str]) -> np.ndarray:
    index = {n: i for i, n in enumerate(names)}
    a = np.array([index[g[0]] for g in games], dtype=int)
    b = np.array([index[g[1]] for g in games], dtype=int)
    return _wins(a, b, np.array([g[2] for g in games], dtype=float), len(names))


def _wins(a: np.ndarray, b: np.ndarray, result: np.ndarray, n: int) -> np.ndarray:
    """wins[i, j]: what i scored against j over the games (a[k] against b[k] scoring result[k])."""
    flat = np.bincount(a * n + b, weights=result, minlength=n * n)
    flat += np.bincount(b * n + a, weights=1 - result, minlength=n * n)
    return flat.reshape(n, n)


def strengths(wins: np.ndarray, steps: int = 50, tol: float = 1e-9) -> np.ndarray:
    """log10 strengths: the maximum of the likelihood with the virtual draw against a reference of
    strength 1, by Newton's method on the natural-log strengths (concave: the prior makes it strictly so)."""
    games = wins + wins.T
    theta = np.zeros(len(wins))
    for _ in range(steps):
        p = 1 / (1 + np.exp(theta[None, :] - theta[:, None]))  # P(i beats j)
        p_ref = 1 / (1 + np.exp(-theta))
        grad = wins.sum(axis=1) - (games * p).sum(axis=1) + 0.5 - p_ref
        curve = games * p * (1 - p)
        hess = curve - np.diag(curve.sum(axis=1) + p_ref * (1 - p_ref))
        step = np.linalg.solve(hess, grad)
        theta -= step
        if np.max(np.abs(step)) < tol:
            break
    return theta / np.log(10)


def elo(log_strengths: np.ndarray, names: Sequence[str], anchor: str | None) -> np.ndarray:
    shift = log_strengths[list(names).index(anchor)] if anchor is not None and anchor in names else log_strengths.mean()
    return 400 * (log_strengths - shift)


def rate(
    games: Sequence[Game],
    names: Sequence[str],
    anchor: str | None = "do_nothing",
    rounds: int = 500,
    confidence: float = 0.95,
    seed: int = 0,
) -> dict[str, BTRating]:
    """Every entrant's rating and bootstrap interval (an entrant without games: 0 with no interval)."""
    names = list(names)
    index = {n: i for i, n in enumerate(names)}
    a = np.array([index[g[0]] for g in games], dtype=int)
    b = np.array([index[g[1]] for g in games], dtype=int)
    result = np.array([g[2] for g in games], dtype=float)
    point = elo(strengths(_wins(a, b, result, len(names))), names, anchor)
    rng = np.random.default_rng(seed)
    samples = np.empty((rounds, len(names)))
    for r in range(rounds):
        pick = rng.integers(0, len(games), len(games))
        samples[r] = elo(strengths(_wins(a[pick], b[pick], result[pick], len(names))), names, anchor)
    tail = (1 - confidence) / 2 * 100
    low, high = np.percentile(samples, [tail, 100 - tail], axis=0)
    played = {n: sum(n in (a, b) for a, b, _ in games) for n in names}
    return {n: BTRating(float(point[i]), float(low[i]), float(high[i]), played[n]) for i, n in enumerate(names)}
