"""A game's result is defined once (stats/result.py) and every reader agrees with it."""

from __future__ import annotations

import numpy as np

from pillagerbench.league.arena_view import games_of
from pillagerbench.metrics.formulas import win_rate
from pillagerbench.rundir.episode import winner_of
from pillagerbench.stats.result import result, results

GAMES = [(5.0, 3.0), (2.0, 2.0), (0.0, 1.5), (1.5, 0.0)]


def test_won_drew_lost():
    assert [result(a, b) for a, b in GAMES] == [1.0, 0.5, 0.0, 1.0]
    assert results([a for a, _ in GAMES], [b for _, b in GAMES]).tolist() == [1.0, 0.5, 0.0, 1.0]
    assert [winner_of(a, b) for a, b in GAMES] == ["red", "tie", "blue", "red"]


def test_the_win_rate_and_the_leagues_games_read_the_same_results():
    red, blue = np.array([a for a, _ in GAMES]), np.array([b for _, b in GAMES])
    assert win_rate(red, blue).mean == (1.0 + 0.5 + 0.0 + 1.0) / 4

    class Out:
        def __init__(self, k, a, b):
            self.red, self.blue, self.red_score, self.blue_score, self.order = "x", "y", a, b, k

    assert [g[2] for g in games_of([Out(k, a, b) for k, (a, b) in enumerate(GAMES)])] == [1.0, 0.5, 0.0, 1.0]
