"""A built-in opponent's player with no runs left rests to the whistle: on the lockstep clock its bot,
idle since its last run, no longer holds the world until the server lets go of it after 5 s of wall
time (each such wait is named in server.log). Nor do the players no team plays (Dash & Dine's
servers), whose bots never run."""

from __future__ import annotations

from pillagerbench.teams.mushroom_war import Passive
from tests.teams.conftest import play_series


class OneShortRun(Passive):
    """Each player runs a few ticks once, then has no runs left."""

    max_runs = 1

    def code_for(self, ctx, index: int) -> str:
        return "await bot.waitForTicks(5)"


async def test_a_player_without_runs_left_lets_the_world_go_on(tmp_path):
    (rec,) = await play_series("mushroom_war", OneShortRun(), "do_nothing", tmp_path, length=10, clock="lockstep")
    assert rec.status == "ok", rec.error
    assert rec.iterations["red"] == [1, 1]
    assert_no_wall_clock_waits(tmp_path / "server.log")


async def test_the_players_no_team_plays_hold_nothing(tmp_path):
    (rec,) = await play_series("dash_and_dine", "do_nothing", "do_nothing", tmp_path, length=120, clock="lockstep")
    assert rec.status == "ok", rec.error
    assert_no_wall_clock_waits(tmp_path / "server.log")


def assert_no_wall_clock_waits(server_log) -> None:
    log = server_log.read_text()
    assert "let go after" not in log, [line for line in log.splitlines() if "let go after" in line]
