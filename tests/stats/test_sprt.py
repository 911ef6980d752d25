"""The sequential test (stats/sprt.py) on simulated pairs: its error rates stay within their bounds,
it stops earlier on average than a fixed-size test at the same error rates, and bad bounds are named."""

from __future__ import annotations

import random

import pytest

from pillagerbench.stats.sample_size import fixed_test
from pillagerbench.stats.sprt import BETTER, NOT_BETTER, UNDECIDED, Bounds, llr, run, verdict

RUNS = 2000  # simulated comparisons per case: an error rate's sampling error is about ±0.005


def simulate(p_ahead: float, bounds: Bounds, seed: int, ties: float = 0.0) -> tuple[dict[str, float], float]:
    """Share of each verdict and the mean pairs used, pairs won with p_ahead (a share `ties` level)."""
    rng = random.Random(seed)

    def pair() -> float:
        if rng.random() < ties:
            return 0.5
        return 1.0 if rng.random() < p_ahead else 0.0

    found = [run(pair, bounds, cap=5000) for _ in range(RUNS)]
    shares = {v: sum(f == v for f, _ in found) / RUNS for v in (BETTER, NOT_BETTER, UNDECIDED)}
    return shares, sum(n for _, n in found) / RUNS


@pytest.mark.parametrize(
    "bounds",
    [Bounds(), Bounds(0.5, 0.6, 0.1, 0.2), Bounds(0.5, 0.65, 0.02, 0.3)],
    ids=["default", "looser", "asymmetric"],  # asymmetric: alpha and beta swapped would break both rates
)
def test_error_rates_stay_within_their_bounds(bounds):
    false_alarm, _ = simulate(bounds.p0, bounds, seed=1)
    miss, _ = simulate(bounds.p1, bounds, seed=2)
    assert false_alarm[BETTER] <= bounds.alpha + 0.01, false_alarm
    assert miss[NOT_BETTER] <= bounds.beta + 0.01, miss
    assert false_alarm[UNDECIDED] == miss[UNDECIDED] == 0  # the cap is far away


def test_level_pairs_count_as_not_better_and_keep_the_error_rates():
    bounds = Bounds()
    shares, _ = simulate(bounds.p0, bounds, seed=3, ties=0.5)
    assert shares[BETTER] <= bounds.alpha + 0.01


@pytest.mark.parametrize("p_ahead", [0.5, 0.65, 0.75, 0.94])
def test_it_stops_earlier_than_a_fixed_size_test_at_the_same_error_rates(p_ahead):
    bounds = Bounds()
    fixed = fixed_test(0.5, bounds.p1 - bounds.p0, bounds.alpha, bounds.beta)
    _, mean_pairs = simulate(p_ahead, bounds, seed=4)
    assert mean_pairs < fixed, (mean_pairs, fixed)


def test_the_ratio_crosses_the_upper_bound_for_a_clear_lead_and_the_lower_for_a_clear_lag():
    bounds = Bounds()
    assert verdict([1.0] * 12, bounds) == BETTER and verdict([1.0] * 11, bounds) == UNDECIDED
    assert verdict([0.0] * 9, bounds) == NOT_BETTER and llr([], bounds) == 0
    assert llr([1.0, 0.0], bounds) == pytest.approx(llr([0.5, 0.5], bounds))


@pytest.mark.parametrize(
    ("bounds", "problem"),
    [
        (Bounds(alpha=0.5), "alpha=0.5: an error rate is in (0, 0.5)"),
        (Bounds(beta=0), "beta=0: an error rate is in (0, 0.5)"),
        (Bounds(p0=0.6, p1=0.5), "p0=0.6, p1=0.5: the bounds are in order, 0 < p0 < p1 < 1"),
        (Bounds(p0=0.5, p1=1.0), "p0=0.5, p1=1.0: the bounds are in order"),
    ],
)
def test_bad_bounds_are_named(bounds, problem):
    assert bounds.problems() and bounds.problems()[0].startswith(problem)
    assert Bounds().problems() == []


@pytest.mark.parametrize("p_ahead", [0.3, 0.5, 0.65, 0.75, 0.94])
def test_walds_approximation_of_the_pairs_is_close_to_the_simulated_mean(p_ahead):
    from pillagerbench.stats.sample_size import sprt_pairs

    b = Bounds()
    _, simulated = simulate(p_ahead, b, seed=6)
    approx = sprt_pairs(p_ahead, b.p0, b.p1, b.alpha, b.beta)
    assert 0.8 * simulated <= approx <= 1.05 * simulated, (approx, simulated)  # it leaves out the overshoot
