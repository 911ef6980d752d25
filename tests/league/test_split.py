"""A league rated on test layouts (issue 29): `split` in league.yaml (or `play`/`board split=test`)
plays every match on fresh test layouts, the board rates only that split's episodes and says so on
every table, an unknown split or a `layout=` override is one line (no server: hand-made rounds)."""

from __future__ import annotations

import csv
import html

import pytest

from pillagerbench.cli.commands import main as cli_main
from pillagerbench.config.schema import RunnerConfig
from pillagerbench.league import results
from pillagerbench.league.board import write_board
from pillagerbench.league.rounds import write_round
from pillagerbench.league.schedule import Pairing
from pillagerbench.league.spec import League, RosterEntry, load_league
from tests.metrics.fake_runs import write_run

TEAMS = ("do_nothing", "passive")


@pytest.fixture
def rounds(tmp_path, monkeypatch):
    """Two rounds of passive (red) against do_nothing: 3 episodes on the paper's layout, 2 on test layouts."""
    paper = write_run(tmp_path / "paper", "mushroom_war", "passive", "do_nothing", [(5, 0)] * 3, layouts=["paper"] * 3)
    test = write_run(tmp_path / "test", "mushroom_war", "passive", "do_nothing", [(2, 0)] * 2, layouts=[10**6, 10**7])
    monkeypatch.setattr(results, "round_dirs", lambda league_dir: [paper, test])
    return tmp_path / "L"


@pytest.mark.parametrize("split, rated, left", [("test", 2, "3 on split paper"), ("paper", 3, "2 on split test")])
def test_the_board_rates_its_split_only_and_says_which(rounds, split, rated, left):
    rounds.mkdir()
    write_board(rounds, League(entrants=[RosterEntry(t, t) for t in TEAMS], split=split))
    board = {r["entrant"]: r for r in csv.DictReader((rounds / "leaderboard.csv").open())}
    assert board["passive"]["episodes"] == str(rated) and {r["split"] for r in board.values()} == {split}
    md = (rounds / "leaderboard.md").read_text()
    on = {"test": "fresh test layouts", "paper": "the paper's layout"}[split]
    assert all(f"(ratings on {on}: split {split})" in line for line in md.splitlines() if line.startswith("## "))
    assert f"- ratings on {on} (split {split}): {rated} of 5 episodes" in md and f"left out: {left}" in md
    assert html.escape(f"(ratings on {on}: split {split})") in (rounds / "leaderboard.html").read_text()


def test_a_test_league_plays_every_match_on_fresh_test_layouts(tmp_path):
    league = League(entrants=[RosterEntry(t, t) for t in TEAMS], split="test")
    _, specs = write_round(tmp_path, league, [Pairing("mushroom_war", *TEAMS)], 2, (), RunnerConfig())
    assert [(s.config.layout, s.config.split) for s in specs] == [("paper", "test")] * 2
    league.split = "paper"
    _, specs = write_round(tmp_path, league, [Pairing("mushroom_war", *TEAMS)], 2, (), RunnerConfig())
    assert [(s.config.layout, s.config.split) for s in specs] == [("paper", None)] * 2


def test_every_match_is_played_with_its_side_swapped_twin_on_the_same_seed(tmp_path):
    league = League(entrants=[RosterEntry(t, t) for t in TEAMS], split="dev")
    _, specs = write_round(tmp_path, league, [Pairing("mushroom_war", *TEAMS)], 2, (), RunnerConfig())
    assert [(s.red, s.blue) for s in specs] == [tuple(TEAMS), tuple(reversed(TEAMS))]
    assert specs[0].seed == specs[1].seed and specs[0].config.split == "dev"  # dev layouts follow the seed


@pytest.mark.parametrize(
    "args, expected",
    [
        (["init", "split=hidden"], "unknown split 'hidden'; known: dev, paper, test"),
        (["board", "split=hidden"], "unknown split 'hidden'; known: dev, paper, test"),
        (["play", "layout=5"], "'layout=5': a league plays on the paper's layout or on fresh layouts of its split"),
    ],
    ids=["init", "board", "play_with_a_layout"],
)
def test_an_unknown_split_or_a_layout_is_one_line(tmp_path, capsys, args, expected):
    root = tmp_path / "L"
    if args[0] != "init":
        assert cli_main(["league", str(root), "init"]) == 0
        capsys.readouterr()
    assert cli_main(["league", str(root), *args]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and err[0].startswith("pillagerbench league: ") and expected in err[0], err
    assert not (root / "matches").exists()


def test_the_split_is_kept_in_league_yaml(tmp_path):
    assert cli_main(["league", str(tmp_path / "L"), "init", "split=test"]) == 0
    assert load_league(tmp_path / "L").split == "test"
