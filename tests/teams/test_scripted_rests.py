"""A built-in opponent's player with no runs left rests to the whistle: on the lockstep clock its bot,
idle since its last run, no longer holds the world until the server lets go of it after 5 s of wall
time (each such wait is named in server.log)."""

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
    log = (tmp_path / "server.log").read_text()
    assert "let go after" not in log, [line for line in log.splitlines() if "let go after" in line]
