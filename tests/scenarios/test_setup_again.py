"""A match whose login fails (ours, no team's fault) logs in once more on a fresh server before its
series is given up: here the server is frozen (SIGSTOP) while the first player logs in, the bot never
spawns, and the second try, on a fresh server, plays."""

from __future__ import annotations

import os
import signal

from pillagerbench.match import Match
from pillagerbench.match.run import set_up
from pillagerbench.scenarios import make_scenario
from pillagerbench.server import ArenaServer
from pillagerbench.teams import make_team


async def test_a_failed_login_is_tried_once_more_on_a_fresh_server(tmp_path, capsys):
    sc = make_scenario("mushroom_war")
    teams = {"red": make_team("passive", sc.key), "blue": make_team("do_nothing", sc.key)}
    async with ArenaServer(log_path=tmp_path / "server.log") as server:
        frozen = server.process.pid
        os.kill(frozen, signal.SIGSTOP)  # the first login gets no answer: its bot never spawns
        match = Match(server, sc, teams, tmp_path / "run", episode_length=3, seed=1)
        try:
            await set_up(match)
            assert server.process.pid != frozen
            assert sorted(p["name"] for p in await server.players()) == sorted(p.name for p in sc.all_players())
            rec = await match.play_episode(0)
            assert rec.status == "ok", rec.error
        finally:
            await match.close()
    said = [line for line in capsys.readouterr().out.splitlines() if line.startswith("login failed")]
    assert len(said) == 1 and "bot did not spawn within" in said[0] and said[0].endswith("once more on a fresh server")
