"""Bradley–Terry ratings with bootstrap intervals (stats/bradley_terry.py) and the pool's maximal
lottery (stats/lottery.py), on simulated games with known strengths."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from pillagerbench.stats.bradley_terry import rate
from pillagerbench.stats.lottery import margins, maximal_lottery, pool_view

TRUE = {"do_nothing": 0.0, "a": 150.0, "b": 300.0, "c": 420.0}  # Elo scale, anchored at do_nothing


def games(rng: np.random.Generator, per_pair: int) -> list[tuple[str, str, float]]:
    out = []
    for x, y in itertools.combinations(TRUE, 2):
        p = 1 / (1 + 10 ** ((TRUE[y] - TRUE[x]) / 400))
        out += [(x, y, float(rng.random() < p)) for _ in range(per_pair)]
    return out


def test_the_fit_finds_the_true_order_and_anchors_do_nothing_at_zero():
    ratings = rate(games(np.random.default_rng(0), 200), list(TRUE), rounds=50)
    assert ratings["do_nothing"].rating == 0
    assert sorted(ratings, key=lambda n: ratings[n].rating) == list(TRUE)
    for name, true in TRUE.items():
        assert abs(ratings[name].rating - true) < 60, (name, ratings[name])
        assert ratings[name].low <= ratings[name].rating <= ratings[name].high
    assert ratings["a"].games == 600


def test_bootstrap_intervals_cover_the_true_rating_about_95_percent_of_the_time():
    rng = np.random.default_rng(1)
    covered = []
    for _ in range(40):
        ratings = rate(games(rng, 30), list(TRUE), rounds=200, seed=int(rng.integers(1 << 30)))
        covered += [ratings[n].low <= TRUE[n] <= ratings[n].high for n in TRUE if n != "do_nothing"]
    share = sum(covered) / len(covered)
    assert 0.88 <= share <= 0.995, share


def test_an_entrant_that_won_every_game_stays_finite():
    ratings = rate([("a", "do_nothing", 1.0)] * 5, ["a", "do_nothing"], rounds=20)
    assert 0 < ratings["a"].rating < 1500 and np.isfinite(ratings["a"].high)


def test_the_maximal_lottery_of_a_cycle_is_uniform_and_a_dominant_entrant_takes_it_all():
    cycle = [("rock", "scissors", 1.0), ("scissors", "paper", 1.0), ("paper", "rock", 1.0)]
    p = maximal_lottery(margins(cycle, ["rock", "paper", "scissors"]))
    assert p == pytest.approx([1 / 3] * 3, abs=0.02)
    view = pool_view(
        [*cycle, ("best", "rock", 1.0), ("best", "paper", 1.0), ("best", "scissors", 1.0)],
        ["rock", "paper", "scissors", "best"],
    )
    assert view["best"][0] == pytest.approx(1.0, abs=0.01) and view["rock"][1] == pytest.approx(-1.0, abs=0.01)
