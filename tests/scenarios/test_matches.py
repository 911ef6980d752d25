"""Short real episodes: every built-in opponent scores against do_nothing (on the lockstep clock: these
test the rules, and game time does not shrink on a loaded machine; each opponent's match on its
scenario's warm server, whose players logged in once for the module); the real clock's lag verdict; a
dying server fails one episode, not the series."""

from __future__ import annotations

import asyncio
import json
import os
import signal

import pytest
import pytest_asyncio

from pillagerbench.host.machine import SERVER_TPS_MIN
from pillagerbench.match import Match
from pillagerbench.rundir import EpisodeRecord
from pillagerbench.scenarios import make_scenario
from pillagerbench.server import ArenaServer
from pillagerbench.teams import TEAMS, make_team
from tests.support.server_clock import clock_of

OPPONENTS = {name: cls.scenarios[0] for name, cls in TEAMS.items() if cls.scenarios}
EPISODE_S = 60
# potato_cookie serves its first food, a batch of cookies, at 57-63 s (its beans are kept: upstream's
# plantCocoaBeans placed no pod; docs/fidelity.md): it plays the paper's 120 s. cake_beetroot serves its
# first beetroot soup after 51-63 s (collecting as collectblock: head turns and 10 ticks after each
# crop; docs/fidelity.md): 90 s
LENGTH = {"potato_cookie": 120, "cake_beetroot": 90}


async def one_episode(
    scenario_key: str,
    red: str,
    blue: str,
    run_dir,
    length: float = EPISODE_S,
    layout: str | int = "paper",
    clock: str = "real",
    **match_options,
):
    sc = make_scenario(scenario_key, layout=layout)  # Dash & Dine's crops grow by vanilla random ticks at speed 200
    teams = {"red": make_team(red, sc.key), "blue": make_team(blue, sc.key)}
    async with ArenaServer(log_path=run_dir / "server.log", clock=clock) as server:
        match = Match(server, sc, teams, run_dir, episode_length=length, seed=1, clock=clock_of(clock), **match_options)
        try:
            await match.setup()
            return await first_episode(match)
        finally:
            await match.close()


async def first_episode(match: Match) -> EpisodeRecord:
    """The match's episode 0, and every player's game mode after it."""
    rec = await match.play_episode(0)
    modes = {p["name"]: p["gamemode"] for p in await match.server.players()}
    # Dash & Dine's servers are creative (unkillable), every team player survival
    assert modes == {p.name: 1 if p.gamemode == "creative" else 0 for p in match.scenario.all_players()}
    return rec


@pytest_asyncio.fixture(scope="module", loop_scope="session")
async def warm(tmp_path_factory):
    """Scenario key -> a match on its own lockstep server, its players logged in (`setup`), never
    played: the opponents' matches below play on its server and players, one after another, as a
    series' episodes do (each episode builds the arena again and resets every player)."""
    root = tmp_path_factory.mktemp("warm")
    hosts: dict[str, Match] = {}

    async def host(key: str) -> None:
        server = ArenaServer(log_path=root / key / "server.log", clock="lockstep")
        teams = {side: make_team("do_nothing", key) for side in ("red", "blue")}
        hosts[key] = Match(server, make_scenario(key), teams, root / key, clock=clock_of("lockstep"))
        await server.start()
        await hosts[key].setup()

    try:
        await asyncio.gather(*(host(key) for key in sorted(set(OPPONENTS.values()))))
        yield hosts
    finally:
        for match in hosts.values():
            await match.close()
            await match.server.stop()


async def warm_episode(
    warm: dict[str, Match], red: str, run_dir, length: float, layout: str | int = "paper"
) -> EpisodeRecord:
    """Episode 0 of `red` against do_nothing on the lockstep clock, a match of its own on the warm
    server and players of its scenario."""
    host = warm[OPPONENTS[red]]
    sc = make_scenario(host.scenario.key, layout=layout)
    teams = {"red": make_team(red, sc.key), "blue": make_team("do_nothing", sc.key)}
    match = Match(host.server, sc, teams, run_dir, episode_length=length, seed=1, clock=clock_of("lockstep"))
    match.players, match.clock = host.players, host.clock  # the host closes them
    return await first_episode(match)


def sc_red0(key):
    return make_scenario(key).side("red").player_names[0]


def sc_blue0(key):
    return make_scenario(key).side("blue").player_names[0]


def test_every_builtin_opponent_has_a_scenario():
    assert set(OPPONENTS) == {
        "aggressive",
        "balanced",
        "passive",
        "slimy",
        "berries",
        "cake_beetroot",
        "melon_pumpkin",
        "potato_cookie",
    }


@pytest.mark.parametrize(
    "pair",
    [
        ("aggressive", "berries"),
        ("balanced", "cake_beetroot"),
        ("passive", "melon_pumpkin"),
        ("slimy", "potato_cookie"),
    ],
)
async def test_builtin_opponents_score_against_do_nothing(tmp_path, warm, pair):
    # two matches at once (one per scenario), each on its scenario's warm server, on the lockstep clock
    recs = await asyncio.gather(
        *(warm_episode(warm, name, tmp_path / name, LENGTH.get(name, EPISODE_S)) for name in pair)
    )
    for name, rec in zip(pair, recs):
        assert rec.status == "ok", rec.error
        assert rec.red_score > 0, f"{name} scored {rec.red_score} against do_nothing in {rec.scenario}"
        # do_nothing may score: its idle players pick up what the opponent breaks next to them
        # (vanilla pickup; the paper: "do_nothing gets non-zero points")
        assert rec.player_order[:2] == [sc_red0(rec.scenario), sc_blue0(rec.scenario)]
        assert not rec.lagged and "clock=lockstep" in rec.lag_reason, rec  # the game waited for every bot
        timeline = json.loads((tmp_path / name / "episode_000" / "timeline.json").read_text())
        length = LENGTH.get(name, EPISODE_S)
        assert [p["t"] for p in timeline] == list(range(length)) + [length]
        assert timeline[-1]["red"] == rec.red_score
        chat = (tmp_path / name / "episode_000" / "chat.txt").read_text().splitlines()
        red_players = make_scenario(rec.scenario).side("red").player_names
        assert any(line.startswith(f"<{p}>") for line in chat for p in red_players)  # the server's chat log
        world = [json.loads(line) for line in open(tmp_path / name / "episode_000" / "world_events.jsonl")]
        assert any(e["event"] == "item_picked_up" for e in world)


async def test_on_the_real_clock_a_starved_server_flags_the_episode(tmp_path):
    rec = await one_episode("mushroom_war", "passive", "do_nothing", tmp_path, length=15)
    assert rec.status == "ok", rec.error
    # the server's own ticks over the game's wall time: never above 20 TPS; whatever the machine's
    # load, below load.SERVER_TPS_MIN the episode is flagged as lagged
    assert 0 < rec.server_tps <= 20.5 and (rec.server_tps >= SERVER_TPS_MIN or rec.lagged), rec
    assert rec.lag_reason is None or "lockstep" not in rec.lag_reason


@pytest.mark.parametrize("pair", [(("aggressive", 1), ("melon_pumpkin", 2))])
async def test_builtin_opponents_score_on_generated_layouts(tmp_path, warm, pair):
    """30 s on a generated layout of each scenario (two matches at once, on the warm servers, on the
    lockstep clock: layouts under game time, issue 38's item 6): the opponents play the layout's places,
    not the paper's, and nothing they do is refused."""
    recs = await asyncio.gather(*(warm_episode(warm, name, tmp_path / name, 30, layout=seed) for name, seed in pair))
    for (name, seed), rec in zip(pair, recs):
        assert rec.status == "ok", rec.error
        assert (rec.layout, rec.split) == (seed, "dev")
        assert rec.red_score > 0, f"{name} scored {rec.red_score} against do_nothing on layout {seed}"
        assert not rec.refusals, rec.refusals


async def test_upstream_scoring_plays_on_to_upstreams_sample_and_records_both_scores(tmp_path):
    rec = await one_episode("mushroom_war", "passive", "do_nothing", tmp_path, length=3, scoring="upstream")
    assert rec.status == "ok", rec.error
    assert rec.scoring == "upstream" and set(rec.scores) == {"clean", "upstream"}
    assert (rec.red_score, rec.blue_score) == (rec.scores["upstream"]["red"], rec.scores["upstream"]["blue"])
    assert rec.runs["Ryn"] >= 1 and rec.runs["Raze"] >= 1 and "Byte" not in rec.runs  # do_nothing runs nothing
    assert rec.game_s >= 3 + 5  # play went on to upstream's "120 s" sample
    ep = tmp_path / "episode_000"
    assert [p["t"] for p in json.loads((ep / "timeline.json").read_text())] == [0, 1, 2, 3]
    upstream = json.loads((ep / "timeline_upstream.json").read_text())
    assert [(p["t"], p["line"]) for p in upstream] == [(5, 0), (6, 1), (7, 2), (8, 3)]
    assert upstream[-1]["red"] == rec.red_score
    saved = json.loads((ep / "episode.json").read_text())
    assert saved["scores"] == rec.scores and saved["protocol"] == "pillagerbench"


async def test_a_dead_server_fails_the_episode_and_the_series_goes_on(tmp_path):
    sc = make_scenario("mushroom_war")
    teams = {"red": make_team("passive", sc.key), "blue": make_team("do_nothing", sc.key)}
    server = ArenaServer(log_path=tmp_path / "server.log")
    await server.start()
    playing = asyncio.Event()  # episode 0's game has run 2 s: the kill comes mid-game, whatever the reset took

    def on_tick(status: dict) -> None:
        if status["episode"] == 0 and status["t"] >= 2:
            playing.set()

    match = Match(server, sc, teams, tmp_path, episode_length=6, seed=1, on_tick=on_tick)
    records = []

    async def kill_during_first_episode():
        await playing.wait()
        os.killpg(server.process.pid, signal.SIGKILL)

    try:
        await match.setup()
        killer = asyncio.create_task(kill_during_first_episode())
        await match.play_episodes([0, 1], records.append)  # restarts the server after the failure
        await killer
        assert [r.status for r in records] == ["failed", "ok"], records[-1].error
        assert "arena server process ended" in records[0].error or "control channel" in records[0].error
        assert json.loads((tmp_path / "episode_000" / "episode.json").read_text())["status"] == "failed"
        assert server.alive
    finally:
        await match.close()
        await server.stop()
