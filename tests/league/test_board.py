"""The league board ranks equal ratings as ties (1, 1, 3), the empty board included, and its page
names the rounds it was built from, or says there are none yet (no server: no rounds played)."""

from __future__ import annotations

import csv

from pillagerbench.league.board import write_board
from pillagerbench.league.ratings import Rating, ranks
from pillagerbench.league.spec import League, RosterEntry

TEAMS = ["do_nothing", "passive", "balanced", "aggressive", "slimy"]


def test_equal_ratings_share_a_rank_and_the_next_one_skips():
    ratings = {n: Rating(mu, 1.0, 4) for n, mu in (("a", 5.0), ("b", 3.0), ("c", 3.0), ("d", 0.0), ("e", -1.0))}
    assert ranks(ratings) == {"a": 1, "b": 2, "c": 2, "d": 4, "e": 5}


def test_the_empty_board_ties_every_entrant_and_says_no_rounds_yet(tmp_path):
    league = League(entrants=[RosterEntry(t, t) for t in TEAMS])
    write_board(tmp_path, league)
    rows = list(csv.DictReader((tmp_path / "leaderboard.csv").open()))
    assert sorted(r["entrant"] for r in rows) == sorted(TEAMS)
    assert [r["rank"] for r in rows] == ["1"] * len(TEAMS)
    page = (tmp_path / "leaderboard.html").read_text()
    assert "<p class='note'>Rounds: none yet</p>" in page
    assert "Runs:" not in page


def test_the_board_has_bradley_terry_ratings_with_intervals_and_the_pools_view(tmp_path, monkeypatch):
    from pillagerbench.league import results
    from tests.metrics.fake_runs import write_run

    rounds = [
        write_run(tmp_path / "r0", "mushroom_war", "passive", "do_nothing", [(20, 0), (22, 0), (18, 0)], suite="s@a"),
        write_run(tmp_path / "r1", "mushroom_war", "balanced", "passive", [(10, 20), (25, 20), (9, 21)], suite="s@a"),
        write_run(tmp_path / "r2", "mushroom_war", "do_nothing", "balanced", [(0, 14), (0, 15)], suite="s@a"),
    ]
    monkeypatch.setattr(results, "round_dirs", lambda league_dir: rounds)
    league = League(entrants=[RosterEntry(t, t) for t in ("do_nothing", "passive", "balanced")])
    write_board(tmp_path, league)
    rows = {r["entrant"]: r for r in csv.DictReader((tmp_path / "leaderboard.csv").open())}
    for column in ("BT rating", "BT 95% low", "BT 95% high", "lottery share", "Nash margin", "LLM cost/win"):
        assert column in rows["passive"], column
    assert float(rows["do_nothing"]["BT rating"]) == 0
    bt = {n: float(r["BT rating"]) for n, r in rows.items()}
    assert bt["passive"] > bt["balanced"] > bt["do_nothing"]
    assert float(rows["passive"]["BT 95% low"]) <= bt["passive"] <= float(rows["passive"]["BT 95% high"])
    assert float(rows["passive"]["lottery share"]) > 0.9 and float(rows["do_nothing"]["Nash margin"]) < 0
    assert "Bradley–Terry" in (tmp_path / "leaderboard.md").read_text()


def test_rating_against_dollars_is_plotted_for_the_entrants_with_a_known_cost(tmp_path):
    import pandas as pd

    from pillagerbench.league.arena_view import cost_plot

    board = pd.DataFrame(
        {
            "entrant": ["cot", "tacticrafter", "passive"],
            "BT rating": [120.0, 180.0, 90.0],
            "BT 95% low": [60.0, 100.0, 40.0],
            "BT 95% high": [190.0, 260.0, 150.0],
            "LLM cost/episode": [0.02, 0.05, float("nan")],
        }
    )
    out = cost_plot(board, tmp_path / "cost.png")
    assert out is not None and out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert cost_plot(board.iloc[2:], tmp_path / "none.png") is None and not (tmp_path / "none.png").exists()
