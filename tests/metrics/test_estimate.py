"""EntrantEstimate, what metrics hands the report for a row: the formulas' P, S, D, W, and the row's
columns in their order (episodes, then each metric's mean and interval)."""

from __future__ import annotations

import math

from pillagerbench.metrics.estimate import COLUMNS, EntrantEstimate
from pillagerbench.metrics.formulas import Estimate, mean_ci, over_opponents, pairing


def test_one_opponent_is_the_pairing_and_several_are_pooled():
    red, blue, sigma = [3.0, 5.0, 4.0], [1.0, 1.0, 2.0], Estimate(2.0, 0.5, 10)
    one = EntrantEstimate.against(red, blue, sigma)
    assert one.episodes == 3 and one == EntrantEstimate.of(pairing(red, blue, 2.0, sigma), 3)
    assert one.D == mean_ci([2.0, 4.0, 2.0]) and one.W.mean == 1.0
    groups = [(red, blue, 2.0, sigma), ([0.0], [4.0], None, None)]
    both = EntrantEstimate.over(groups)
    assert both.episodes == 4 and both == EntrantEstimate.of(over_opponents(groups), 4)
    assert both.P == mean_ci([3.0, 5.0, 4.0, 0.0])


def test_a_row_has_the_episodes_then_each_metrics_mean_and_interval():
    row = EntrantEstimate.against([2.0], [1.0], None).columns()
    assert list(row) == ["episodes", *COLUMNS] == ["episodes", "P", "P_ci", "S", "S_ci", "D", "D_ci", "W", "W_ci"]
    assert (row["episodes"], row["P"], row["D"], row["W"]) == (1, 2.0, 1.0, 1.0)
    assert math.isnan(row["P_ci"]) and math.isnan(row["S"])  # one episode: no interval; no σ: no S
