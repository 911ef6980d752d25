"""A small league of built-in teams on the real server: init, add, play scheduled matches, killed
mid-episode (SIGKILL to its process group) and played again (the round is resumed, nothing lost or
repeated), the board consistent with the episodes; bad input refused with one line, nothing played."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import time
from pathlib import Path

import pandas as pd
import pytest

from pillagerbench.rundir import EpisodeRecord, spoiled
from tests.support.cli import run_cli, start_cli

PLAY = [
    "play",
    "budget.episodes=6",
    "episodes_per_match=2",
    "episode_length=10",
    "clock=lockstep",
    "parallel=2",
    "display=plain",
]


def league(*args: str, **kw):
    return start_cli("league", *args, **kw)


def done(*args: str) -> subprocess.CompletedProcess:
    return run_cli(Path.cwd(), "league", *args)


def lines(path: Path) -> list[dict]:
    return [json.loads(x) for x in path.read_text().splitlines()] if path.exists() else []


def all_series(root: Path) -> list[Path]:
    return sorted((root / "matches").glob("round_*/series/*"))


@pytest.fixture(scope="module")
def played(tmp_path_factory):
    root = tmp_path_factory.mktemp("league") / "L"
    assert done(str(root), "init", "scenarios=[mushroom_war]").returncode == 0
    added = done(str(root), "add", "balanced_2", "team=balanced")
    assert added.returncode == 0, added.stderr
    proc = league(str(root), *PLAY)
    deadline = time.monotonic() + 150
    try:
        while time.monotonic() < deadline:  # kill while a series plays its second episode
            live = [
                s for s in all_series(root) if len(lines(s / "episodes.jsonl")) == 1 and (s / "episode_001").exists()
            ]
            if live:
                break
            assert proc.poll() is None, proc.stdout.read()
            time.sleep(0.2)
        else:
            pytest.fail("the league never reached a second episode")
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    before = {s: lines(s / "episodes.jsonl") for s in all_series(root)}
    again = league(str(root), *PLAY)
    out, _ = again.communicate(timeout=300)
    assert again.returncode == 0, out
    return root, before, out


def used(recs: list[dict]) -> list[dict]:
    """The records that are results: an episode spoiled on our side (e.g. played under lag on a
    loaded machine) is kept, replayed, and counted in the budget, never on the board."""
    return [r for r in recs if not spoiled(EpisodeRecord.from_dict(r))]


def test_the_killed_round_is_finished_and_the_budget_stops_the_league(played):
    root, before, out = played
    finished = {s: lines(s / "episodes.jsonl") for s in all_series(root)}
    played_here = sum(len(v) for v in finished.values())
    assert "finishing round_000" in out and f"league stopped: budget spent (episodes {played_here}/6)" in out
    # the last round was begun with budget left, and its replays of spoiled episodes may take it over
    last_round = sorted({s.parent.parent for s in finished})[-1]
    assert played_here - sum(len(v) for s, v in finished.items() if s.parent.parent == last_round) < 6 <= played_here
    for s, recs in finished.items():
        assert [r["episode"] for r in recs] == list(range(len(recs))), s
        assert recs[: len(before.get(s, []))] == before.get(s, [])  # nothing finished was lost or replayed
    assert any((s / "discarded").exists() for s in finished)


def test_the_board_matches_the_episodes_and_is_reproducible(played):
    root = played[0]
    board = pd.read_csv(root / "leaderboard.csv")
    episodes = {}
    for s in all_series(root):
        spec = json.loads((s / "series.json").read_text())
        for _ in used(lines(s / "episodes.jsonl")):
            for side in ("red", "blue"):
                episodes[spec[side]] = episodes.get(spec[side], 0) + 1
    assert dict(zip(board["entrant"], board["episodes"])) == {n: episodes.get(n, 0) for n in board["entrant"]}
    assert set(board["entrant"]) == {"do_nothing", "aggressive", "balanced", "passive", "slimy", "balanced_2"}
    assert board.loc[board["entrant"] == "do_nothing", "rating"].item() == 0
    first = (root / "leaderboard.csv").read_text()
    assert done(str(root), "board").returncode == 0
    assert (root / "leaderboard.csv").read_text() == first
    page = (root / "leaderboard.html").read_text()
    assert "Head to head, mushroom_war" in page and "http" not in page.replace("http-equiv", "")


def test_bad_input_is_one_line_and_plays_nothing(played):
    root = played[0]
    rounds = sorted(p.name for p in (root / "matches").iterdir())
    spent = done(str(root), *PLAY)
    assert spent.returncode == 2 and spent.stderr.count("\n") == 1 and "budget already spent" in spent.stderr
    other = done(str(root), *PLAY[:3], "budget.episodes=8", "episode_length=12")
    assert other.returncode == 2 and "game overrides" in other.stderr
    twice = done(str(root), "add", "balanced_2", "team=balanced")
    assert twice.returncode == 2 and "exists already" in twice.stderr
    assert sorted(p.name for p in (root / "matches").iterdir()) == rounds
