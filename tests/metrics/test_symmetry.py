"""Side symmetry: each team's points as red vs as blue, per pairing, with Welch intervals."""

from __future__ import annotations

import math

import numpy as np

from pillagerbench.metrics.symmetry import side_symmetry, welch
from pillagerbench.metrics.verified import load_runs
from pillagerbench.report.symmetry import main as symmetry_main
from tests.metrics.fake_runs import write_run


def test_welch_interval_matches_the_textbook_formula():
    a, b = [10, 12, 14, 11], [8, 9, 7, 9, 8]
    e = welch(a, b)
    va, vb = np.var(a, ddof=1) / 4, np.var(b, ddof=1) / 5
    assert math.isclose(e.mean, np.mean(a) - np.mean(b))
    df = (va + vb) ** 2 / (va**2 / 3 + vb**2 / 4)
    assert 4 < df < 5
    # t(0.975, df≈4.6) lies between t(4)=2.776 and t(5)=2.571
    assert 2.571 * math.sqrt(va + vb) < e.ci < 2.776 * math.sqrt(va + vb)
    assert math.isnan(welch([1], [2, 3]).ci)


def test_a_side_edge_is_flagged_and_a_fair_pairing_is_not(tmp_path):
    # "passive" scores 25 as red and 0 as blue against "balanced"; balanced is the same either way
    write_run(tmp_path / "ab", "mushroom_war", "balanced", "passive", [(20, 0), (21, 1), (19, 0)])
    write_run(tmp_path / "ba", "mushroom_war", "passive", "balanced", [(25, 20), (24, 21), (26, 19)])
    table, notes = side_symmetry(load_runs([tmp_path / "ab", tmp_path / "ba"]).episodes)
    assert notes == []
    rows = {r.team: r for r in table.itertuples()}
    assert rows["passive"].no_side_effect == "✗" and math.isclose(rows["passive"].red_minus_blue, 25 - 1 / 3)
    assert rows["balanced"].no_side_effect == "✓" and rows["balanced"].n_red == rows["balanced"].n_blue == 3


def test_a_mirror_match_compares_red_and_blue_of_the_same_episodes(tmp_path):
    write_run(tmp_path / "m", "dash_and_dine", "berries", "berries", [(100, 110), (120, 90), (95, 105)])
    table, _ = side_symmetry(load_runs([tmp_path / "m"]).episodes)
    assert len(table) == 1
    row = table.iloc[0]
    assert row["team"] == row["opponent"] == "berries"
    assert math.isclose(row["as_red"], 31.5 / 3) and math.isclose(row["as_blue"], 30.5 / 3)  # ×0.1
    assert row["no_side_effect"] == "✓"


def test_one_order_only_says_so_in_one_line_and_prints_what_it_can(tmp_path, capsys):
    write_run(tmp_path / "ab", "mushroom_war", "balanced", "passive", [(20, 0), (21, 1)])
    assert symmetry_main([str(tmp_path / "ab")]) == 0
    out = capsys.readouterr().out.splitlines()
    one_order = [line for line in out if "one order only" in line]
    assert len(one_order) == 1 and "play passive red vs balanced blue" in one_order[0]
    assert any(line.startswith("| mushroom_war | balanced | passive | 2 |") for line in out)
    assert out[-1] == "2 comparison(s): 0 ✓, 0 ✗, 2 without an interval"


def test_not_a_run_directory_is_one_line(tmp_path, capsys):
    assert symmetry_main([str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "not a run directory" in err[0]
