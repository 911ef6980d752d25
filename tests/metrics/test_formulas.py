"""The paper's metric formulas against values computed by hand."""

from __future__ import annotations

import math

import pytest

from pillagerbench.metrics import formulas as F


def test_points_difference_win_rate_sabotage_by_hand():
    red, blue = [3, 5, 4, 0], [1, 5, 6, 0]
    m = F.pairing(red, blue, sigma_blue=4.0)
    assert m["P"].mean == 3.0  # (3+5+4+0)/4
    assert m["D"].mean == 0.0  # (2+0-2+0)/4
    assert m["W"].mean == 0.5  # (1 + 0.5 + 0 + 0.5)/4: ties count half
    assert m["S"].mean == 1.0  # 4 - (1+5+6+0)/4
    # 95 % CI of P: t(3) * sd / sqrt(n) = 3.182 * sqrt(14/3) / 2
    assert m["P"].ci == pytest.approx(3.182 * math.sqrt(14 / 3) / 2, rel=1e-6)
    assert m["P"].n == 4


def test_all_opponents_pools_p_d_w_and_averages_s():
    groups = [([2, 4], [1, 1], 3.0, None), ([0], [2], 1.0, None)]
    m = F.over_opponents(groups)
    assert m["P"].mean == pytest.approx(2.0)  # (2+4+0)/3, pooled over episodes
    assert m["D"].mean == pytest.approx(2 / 3)  # (1+3-2)/3
    assert m["W"].mean == pytest.approx(2 / 3)  # (1+1+0)/3
    assert m["S"].mean == pytest.approx(0.5)  # mean of S_A = 3-1 = 2 and S_B = 1-2 = -1


def test_sabotage_without_calibration_is_empty_and_with_sigma_uncertainty_is_welch():
    assert math.isnan(F.sabotage([1, 2], None).mean)
    plain = F.sabotage([1, 2, 3], 5.0)
    both = F.sabotage([1, 2, 3], 5.0, F.mean_ci([4, 5, 6]))
    assert plain.mean == both.mean == 3.0
    assert plain.ci == pytest.approx(4.303 / math.sqrt(3))  # t(2) * sd 1 / sqrt(3)
    # se² = 1/3 + 1/3; Welch df = (2/3)² / (2 · (1/3)² / 2) = 4; t(4) = 2.776
    assert both.ci == pytest.approx(2.776 * math.sqrt(2 / 3))


def test_t_critical_table_and_interpolation():
    assert F.t_critical(4) == 2.776
    assert 2.021 < F.t_critical(35) < 2.042
    assert F.t_critical(10_000) == pytest.approx(1.96, abs=0.01)
    assert math.isnan(F.mean_ci([7]).ci) and F.mean_ci([7]).mean == 7


def test_llm_metrics_follow_the_paper():
    records = [
        {"latency_s": 2.0, "output_tokens": 100},
        {"latency_s": 0.01, "output_tokens": 100, "cache_hit": True, "orig_latency_s": 4.0},  # counts as 4 s
        {"latency_s": 9.0, "output_tokens": 0, "error_type": "LLMTimeout"},  # failed: not counted
    ]
    m = F.llm_metrics(records)
    assert m["calls"] == 2
    assert m["T_resp"] == 3.0  # (2+4)/2
    assert m["N_out"] == 100.0
    assert m["R_tps"] == pytest.approx(37.5)  # mean(100/2, 100/4): the paper's per-call mean
    assert m["r_tps_total"] == pytest.approx(200 / 6)


def test_iterations_mean_over_episodes_of_the_mean_over_players():
    assert F.iterations([[1, 3], [2, 2], [1, 1]]).mean == pytest.approx((2 + 2 + 1) / 3)


def test_dash_and_dine_scaled_by_a_tenth():
    assert F.SCORE_SCALE == {"mushroom_war": 1.0, "dash_and_dine": 0.1}
