"""Same seed, same episode (issue 38, item 4): on the lockstep clock, two episodes of built-in teams
with the same seed give the same score timeline and the same world events, on the real server with
real bots, in a full two-team match; another seed gives another game. Mushroom War only: in Dash &
Dine crops grow and hens lay between the arena's build and the game's start, for as long as the reset
takes on the wall clock (as on the real clock), so on a loaded machine its episodes can part
(docs/clock.md)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.support.cli import run_cli

GAMES = {"mushroom_war": ["red=balanced", "blue=aggressive"]}


def play(tmp_path: Path, name: str, scenario: str, seed: int) -> tuple[list, list[str]]:
    run = tmp_path / name
    args = [f"scenario={scenario}", *GAMES[scenario], "clock=lockstep", f"seed={seed}", "episode_length=30"]
    res = run_cli(tmp_path, "run", *args, f"run_dir={run}", "display=plain", timeout=240)
    assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-2000:]
    episode = run / "episode_000"
    timeline = json.loads((episode / "timeline.json").read_text())
    events = [json.loads(line) for line in (episode / "world_events.jsonl").read_text().splitlines()]
    after = [i for i, e in enumerate(events) if e.get("after_whistle")]
    assert after == list(range(len(events) - len(after), len(events)))  # what came after the whistle: last
    return timeline, [json.dumps(e) for e in events if not e.get("after_whistle")]  # the game's own


@pytest.mark.timeout(600)
@pytest.mark.parametrize("scenario", sorted(GAMES))
def test_the_same_seed_plays_the_same_episode(tmp_path, scenario):
    first, again, other = (play(tmp_path, name, scenario, seed) for name, seed in (("a", 5), ("b", 5), ("c", 6)))
    assert len(first[1]) > 10, first[1]  # a game was played: blocks dug, items picked up
    assert again[0] == first[0], "the score timelines part"
    assert all("tick" in json.loads(line) for line in first[1])  # each event names its moment
    # the same events in the same order: by tick, and within one tick in a fixed order (a dig's event
    # and the game master's announcement of that moment reach the log in either order)
    assert again[1] == first[1], [(a, b) for a, b in zip(first[1], again[1]) if a != b][:2] or len(again[1])
    assert sorted(other[1]) != sorted(first[1])  # the seed decides
