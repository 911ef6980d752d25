"""A real episode on a generated layout, of each scenario: the replay page's map (headless Chromium,
read from the canvas) draws that layout's blocks, where the paper's map would differ, and its
players at that layout's spawns; the live view looks at that layout's middle (its state.json)."""

from __future__ import annotations

import asyncio
import json
import urllib.request

import pytest

from pillagerbench.match import Match
from pillagerbench.replay.page import write_replay
from pillagerbench.scenarios import make_scenario
from pillagerbench.server import ArenaServer
from pillagerbench.teams import make_team
from tests.support.browser import chromium
from tests.support.map_cells import at_spawns, drawn, probe_cells

LAYOUTS = {"mushroom_war": 42, "dash_and_dine": 1}  # 1: Dash & Dine's red base in the south, unlike the paper's
LENGTH = 3
CELL = 13  # pixels: a block on the smaller map (Mushroom War's)


@pytest.fixture(scope="module")
def episodes(tmp_path_factory):
    """Per scenario: its episode directory and what the live view said during the episode."""
    out_dir = tmp_path_factory.mktemp("generated")
    out: dict = {}

    async def play():
        async with ArenaServer(log_path=out_dir / "server.log", watch=0) as server:
            for name, seed in LAYOUTS.items():
                sc = make_scenario(name, layout=seed)
                teams = {side: make_team("do_nothing", name) for side in ("red", "blue")}
                match = Match(server, sc, teams, out_dir / name, episode_length=LENGTH, seed=1)
                try:
                    await match.setup()
                    rec = await match.play_episode(0)
                    assert rec.status == "ok", rec.error
                    state = await asyncio.to_thread(urllib.request.urlopen, server.watch_url + "state.json", timeout=10)
                    out[name] = (out_dir / name / "episode_000", json.loads(state.read()))
                finally:
                    await match.close()

    asyncio.run(play())
    return out


@pytest.mark.timeout(300)
@pytest.mark.parametrize("name", list(LAYOUTS))
def test_the_replay_page_and_the_live_view_show_the_layout_played(episodes, name):
    chromium()
    episode, live = episodes[name]
    page, _ = write_replay(episode)
    scenario, paper = make_scenario(name, layout=LAYOUTS[name]), make_scenario(name)
    players = scenario.all_players()
    near = [(p.spawn[0], p.spawn[2]) for p in players] + [(m[1][0], m[1][2]) for m in scenario.arena.mobs]
    cells = probe_cells(scenario.arena.blocks, paper.arena.blocks, near)
    result = drawn(page, cells, players, at=1.0)  # the arena as built, every player (doing nothing) at its spawn
    assert result["console_errors"] == []
    wrong = [c for c in result["cells"] if c[3] != c[4]]
    assert not wrong, wrong[:5]
    assert len(cells) >= 15 and sum(c[2] == "grass_block" for c in result["cells"]) >= 5
    assert at_spawns(result, slack=0.6 * CELL) == []
    # the live view: the middle of this layout's sides, not the paper's
    middle = [sum(s.center[i] for s in scenario.sides) / 2 for i in range(3)]
    assert live["center"] == pytest.approx(middle) and live["title"] == scenario.title
