"""A game's result, the one definition every reader uses: 1 for the side ahead in points, 0.5 level,
0 behind (the win rate W, a compare's pairs, the league's ratings, an episode's winner)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

WON, DREW, LOST = 1.0, 0.5, 0.0


def result(own: float, other: float) -> float:
    """One game's result for the side with `own` points against `other`."""
    return WON if own > other else DREW if own == other else LOST


def results(own: Sequence[float] | np.ndarray, other: Sequence[float] | np.ndarray) -> np.ndarray:
    """`result` over paired arrays of points."""
    a, b = np.asarray(own, dtype=float), np.asarray(other, dtype=float)
    return np.where(a > b, WON, np.where(a == b, DREW, LOST))
