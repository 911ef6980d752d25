"""Differences between entrants use the paired design where the episodes pair up (the same
opponent, side, layout and seed): on worlds that move both entrants' points alike, the paired
interval is narrower than the unpaired one; without shared worlds the difference is unpaired."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pillagerbench.metrics.paired import by_entrant, difference, differences


def episodes(worlds: list[tuple[str, int]], shift_b: int = 0) -> pd.DataFrame:
    """A and B each against O (red side) on the given worlds; a world gives both the same bonus."""
    rng = np.random.default_rng(5)
    rows = []
    for layout, seed in worlds:
        bonus = rng.normal(0, 8)  # what the world gives any team: large against the entrants' gap
        for entrant, skill in (("A", 20.0), ("B", 17.0)):
            s = seed + (shift_b if entrant == "B" else 0)
            rows.append(
                {
                    "scenario": "mushroom_war",
                    "red": entrant,
                    "blue": "O",
                    "layout": layout,
                    "seed": s,
                    "red_score": skill + bonus + rng.normal(0, 1),
                    "blue_score": 0.0,
                }
            )
    return pd.DataFrame(rows)


WORLDS = [(str(1000 + k), 26000 + k) for k in range(12)]


def test_pairs_on_shared_worlds_give_a_narrower_interval_than_two_means():
    table = differences(by_entrant(episodes(WORLDS)))
    row = table[(table["side"] == "red") & (table["a"] == "A")].iloc[0]
    assert row["design"] == "paired (12 pairs)" and row["opponent"] == "O"
    assert abs(row["a_minus_b"] - 3.0) < 1.5
    assert row["a_minus_b_ci"] < row["unpaired_ci"] / 3, row


def test_without_shared_worlds_the_difference_is_unpaired():
    view = by_entrant(episodes(WORLDS, shift_b=500))
    a, b = (view[(view["side"] == "red") & (view["entrant"] == e)] for e in ("A", "B"))
    found = difference(a, b, "points")
    assert found.design == "unpaired" and found.estimate == found.unpaired
    no_worlds = view.drop(columns=["layout", "seed"])
    assert (
        difference(no_worlds[no_worlds["entrant"] == "A"], no_worlds[no_worlds["entrant"] == "B"], "points").design
        == "unpaired"
    )


def test_a_world_played_twice_by_one_entrant_does_not_pair():
    doubled = episodes(WORLDS[:2] + WORLDS[:1])
    view = by_entrant(doubled)
    a, b = (view[(view["side"] == "red") & (view["entrant"] == e)] for e in ("A", "B"))
    assert difference(a, b, "points").design == "unpaired"  # one world left once each: fewer than 2 pairs


def test_the_report_has_the_differences_paired_where_the_runs_share_their_worlds(tmp_path):
    import csv

    from pillagerbench.report.build import build_report
    from tests.metrics.fake_runs import write_run

    data = episodes(WORLDS)
    runs = []
    for entrant in ("A", "B"):
        mine = data[data["red"] == entrant]
        scores = [(float(s), 0.0) for s in mine["red_score"]]
        layouts = [int(x) for x in mine["layout"]]
        runs.append(
            write_run(
                tmp_path / entrant, "mushroom_war", entrant, "O", scores, layouts=layouts, seeds=list(mine["seed"])
            )
        )
    build_report(runs, tmp_path / "report", with_replays=False)
    (row,) = [r for r in csv.DictReader((tmp_path / "report" / "differences.csv").open()) if r["side"] == "red"]
    assert (row["a"], row["b"], row["design"]) == ("A", "B", "paired (12 pairs)")
    assert float(row["a_minus_b_ci"]) < float(row["unpaired_ci"]) / 3


def test_no_episodes_give_an_empty_table_with_its_columns():
    from pillagerbench.metrics.paired import COLUMNS

    table = differences(by_entrant(pd.DataFrame()))
    assert list(table.columns) == COLUMNS and not len(table)
