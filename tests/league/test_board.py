"""The league board ranks equal ratings as ties (1, 1, 3), the empty board included, and its page
names the rounds it was built from, or says there are none yet (no server: no rounds played)."""

from __future__ import annotations

import csv

from pillagerbench.league.board import write_board
from pillagerbench.league.ratings import Rating, ranks
from pillagerbench.league.spec import Entrant, League

TEAMS = ["do_nothing", "passive", "balanced", "aggressive", "slimy"]


def test_equal_ratings_share_a_rank_and_the_next_one_skips():
    ratings = {n: Rating(mu, 1.0, 4) for n, mu in (("a", 5.0), ("b", 3.0), ("c", 3.0), ("d", 0.0), ("e", -1.0))}
    assert ranks(ratings) == {"a": 1, "b": 2, "c": 2, "d": 4, "e": 5}


def test_the_empty_board_ties_every_entrant_and_says_no_rounds_yet(tmp_path):
    league = League(entrants=[Entrant(t, t) for t in TEAMS])
    write_board(tmp_path, league)
    rows = list(csv.DictReader((tmp_path / "leaderboard.csv").open()))
    assert sorted(r["entrant"] for r in rows) == sorted(TEAMS)
    assert [r["rank"] for r in rows] == ["1"] * len(TEAMS)
    page = (tmp_path / "leaderboard.html").read_text()
    assert "<p class='note'>Rounds: none yet</p>" in page
    assert "Runs:" not in page
