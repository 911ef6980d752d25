"""A match whose login fails (ours, no team's fault) logs in once more on a fresh server before its
series is given up: here the server is frozen (SIGSTOP) while the first player logs in, the bot never
spawns, and the second try, on a fresh server, plays."""

from __future__ import annotations

import inspect
import os
import signal

import pillagerbench.match.match
from pillagerbench.match import Match
from pillagerbench.match.run import set_up
from pillagerbench.players import Player
from pillagerbench.scenarios import make_scenario
from pillagerbench.server import ArenaServer
from pillagerbench.teams import make_team

# the login on the frozen server is given up after this, not the default 30 s (for a loaded machine):
# a frozen server never answers; every later login, on the fresh server, keeps the default
FROZEN_LOGIN_S = 5.0
DEFAULT_LOGIN_S = inspect.signature(Player).parameters["login_timeout"].default


async def test_a_failed_login_is_tried_once_more_on_a_fresh_server(tmp_path, capsys, monkeypatch):
    sc = make_scenario("mushroom_war")
    teams = {"red": make_team("passive", sc.key), "blue": make_team("do_nothing", sc.key)}
    first = [FROZEN_LOGIN_S]

    def player(*args, **kw) -> Player:
        return Player(*args, **kw, **({"login_timeout": first.pop()} if first else {}))

    monkeypatch.setattr(pillagerbench.match.match, "Player", player)
    async with ArenaServer(log_path=tmp_path / "server.log") as server:
        frozen = server.process.pid
        os.kill(frozen, signal.SIGSTOP)  # the first login gets no answer: its bot never spawns
        match = Match(server, sc, teams, tmp_path / "run", episode_length=3, seed=1)
        try:
            await set_up(match)
            assert server.process.pid != frozen
            assert sorted(p["name"] for p in await server.players()) == sorted(p.name for p in sc.all_players())
            assert [p.bot.login_timeout for p in match.players.values()] == [DEFAULT_LOGIN_S] * 4
            rec = await match.play_episode(0)
            assert rec.status == "ok", rec.error
        finally:
            await match.close()
    said = [line for line in capsys.readouterr().out.splitlines() if line.startswith("login failed")]
    assert len(said) == 1 and f"bot did not spawn within {FROZEN_LOGIN_S} s" in said[0]
    assert said[0].endswith("once more on a fresh server")
