"""A short real episode (Mushroom War, aggressive vs balanced) records from the server's truth:
frames at >= 5 Hz for every player, positions equal to the server's, held items, block changes,
items with who picked them up, the score timeline and every program run."""

from __future__ import annotations

import json

import pytest

from pillagerbench.match import Match
from pillagerbench.replay.page import page_data
from pillagerbench.replay.read import load_replay
from pillagerbench.scenarios import make_scenario
from pillagerbench.server import ArenaServer
from pillagerbench.teams import make_team

LENGTH = 15


@pytest.fixture(scope="module")
def episode(tmp_path_factory):
    import asyncio

    run_dir = tmp_path_factory.mktemp("recorded")
    truth: dict = {}

    async def play():
        sc = make_scenario("mushroom_war", crop_growth_chance=0.0)
        teams = {"red": make_team("aggressive", sc.key), "blue": make_team("balanced", sc.key)}
        async with ArenaServer(log_path=run_dir / "server.log") as server:
            match = Match(server, sc, teams, run_dir, episode_length=LENGTH, seed=3)
            try:
                await match.setup()
                rec = await match.play_episode(0)
                truth["players"] = await server.players()  # where the server says they stand now
                return rec
            finally:
                await match.close()

    rec = asyncio.run(play())
    assert rec.status == "ok", rec.error
    return run_dir / "episode_000", truth


def test_a_real_episode_is_recorded_from_the_server(episode):
    ep, truth = episode
    replay = load_replay(ep)
    assert replay.complete, replay.problem
    h = replay.header
    assert h["sides"]["red"]["team"] == "aggressive" and h["length"] == LENGTH
    frames = [r for r in replay.records if r["type"] == "frame"]
    names = {p for side in h["sides"].values() for p in side["players"]}
    # >= 5 Hz for every player, over the whole game
    assert len(frames) >= 5 * LENGTH
    gaps = [b["t"] - a["t"] for a, b in zip(frames, frames[1:])]
    assert max(gaps) < 0.5, max(gaps)
    assert all({p[0] for p in f["players"]} == names for f in frames)
    # the last frame is the server's truth after the whistle (players stand still once stopped)
    last = {p[0]: p[1:4] for p in frames[-1]["players"]}
    for p in truth["players"]:
        assert last[p["name"]] == pytest.approx(p["pos"], abs=0.6), (p, last[p["name"]])
    # players moved, held something, changed blocks; items picked up by someone
    data = page_data(replay)
    moved = [n for n, tr in data["tracks"].items() if abs(tr[0][1] - tr[-1][1]) + abs(tr[0][3] - tr[-1][3]) > 1]
    assert len(moved) >= 2, data["tracks"].keys()
    assert any(f[6] for f in frames[-1]["players"]) or any(p[6] for f in frames for p in f["players"])
    assert any(r["type"] == "blocks_changed" for r in replay.records)
    gone = [r for r in replay.records if r["type"] == "item_gone"]
    assert any(r["by"] in names for r in gone), gone[:5]
    # scores: the episode's timeline, second by second, and the final score
    timeline = json.loads((ep / "timeline.json").read_text())
    scores = [{"t": r["t"], **r["scores"]} for r in replay.records if r["type"] == "score"]
    assert scores == timeline
    assert replay.records[-1]["scores"] == {k: timeline[-1][k] for k in ("red", "blue")}
    # programs: each player's runs start (the scripted teams run one program each)
    starts = {r["player"] for r in replay.records if r["type"] == "program" and r["what"] == "start"}
    assert starts == names
    # chat: every line of chat.txt is in the recording
    chat = [r["event"] for r in replay.records if r["type"] == "event" and r["event"].get("event") == "chat"]
    lines = [(f"<{e['player']}> " if e.get("player") else "") + e["message"] for e in chat]
    assert lines == (ep / "chat.txt").read_text().splitlines()
