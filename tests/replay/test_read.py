"""Replays from bad input: an episode without a recording (an older run), a truncated recording (a
killed run; it still plays up to where it ends), a corrupt one, a directory that is no episode:
`pillagerbench replay` says so in one line (exit 2) or, when there is something to play, writes
the page and notes what is missing."""

from __future__ import annotations

import gzip
import shutil
from pathlib import Path

import pytest

from pillagerbench.replay.page import PAGE, page_data
from pillagerbench.replay.read import ReplayError, load_replay
from tests.support.cli import run_cli

FIXTURE = Path(__file__).with_name("fixtures") / "episode_000"


@pytest.fixture
def episode(tmp_path) -> Path:
    ep = tmp_path / "run" / "episode_000"
    shutil.copytree(FIXTURE, ep)
    return ep


def test_the_fixture_is_complete_and_plays_the_whole_episode(episode):
    replay = load_replay(episode)
    assert replay.complete and replay.problem is None
    data = page_data(replay)
    assert data["duration"] == pytest.approx(30, abs=0.5)
    assert set(data["tracks"]) == {"Ryn", "Raze", "Byte", "Blink"}
    # >= 5 Hz for every player
    assert all(len(track) >= 5 * 29 for track in data["tracks"].values())
    assert data["scores"][-1] == {"t": 30.0, "red": 4.0, "blue": 4.0}


def test_a_truncated_recording_plays_up_to_where_it_ends(episode):
    path = episode / "replay.jsonl.gz"
    raw = gzip.decompress(path.read_bytes())
    path.write_bytes(gzip.compress(raw)[: len(gzip.compress(raw)) // 2])  # a run killed mid-write
    replay = load_replay(episode)
    assert replay.problem and "cut short" in replay.problem
    assert 2 < replay.duration < 29
    proc = run_cli(episode.parent, "replay", str(episode))
    assert proc.returncode == 0, proc.stderr
    assert (episode / PAGE).exists()
    assert proc.stderr.strip().count("\n") == 0 and "cut short" in proc.stderr
    assert "cut short" in (episode / PAGE).read_text()  # the page says it too


def test_a_recording_without_its_end_still_plays(episode):
    path = episode / "replay.jsonl.gz"
    lines = gzip.decompress(path.read_bytes()).splitlines(keepends=True)
    path.write_bytes(gzip.compress(b"".join(lines[: len(lines) // 3])))
    replay = load_replay(episode)
    assert replay.problem and "no end" in replay.problem
    assert replay.duration > 1


def test_a_corrupt_line_ends_the_replay_there(episode):
    path = episode / "replay.jsonl.gz"
    lines = gzip.decompress(path.read_bytes()).splitlines(keepends=True)
    lines[100] = b"{not json\n"
    path.write_bytes(gzip.compress(b"".join(lines)))
    replay = load_replay(episode)
    assert replay.problem and "line 101" in replay.problem
    assert len(replay.records) == 99


@pytest.mark.parametrize(
    "damage, expected",
    [
        ("missing", "no replay recording (replay.jsonl.gz): it was played before replays were recorded"),
        ("garbage", "is not a readable replay recording"),
        ("not_episode", "is not an episode directory"),
        ("not_dir", "is not a directory"),
    ],
)
def test_nothing_to_play_is_one_line_and_exit_2(episode, damage, expected):
    target = episode
    if damage == "missing":
        (episode / "replay.jsonl.gz").unlink()
    elif damage == "garbage":
        (episode / "replay.jsonl.gz").write_bytes(b"this is not gzip at all\n")
    elif damage == "not_episode":
        target = episode.parent / "empty"
        target.mkdir()
    else:
        target = episode / "chat.txt"
    with pytest.raises(ReplayError):
        load_replay(target)
    proc = run_cli(episode.parent, "replay", str(target))
    assert proc.returncode == 2
    err = proc.stderr.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("pillagerbench replay: ") and expected in err[0], proc.stderr
    assert not (target / PAGE).exists() if target.is_dir() else True
