"""A built-in opponent's player with no runs left rests to the whistle: on the lockstep clock its bot,
idle since its last run, no longer holds the world until the server lets go of it after 5 s of wall
time (each such wait is named in server.log). Nor do the players no team plays (Dash & Dine's
servers), whose bots never run, nor those of a team whose play is over (returned or failed) while the
game goes on: with scoring=upstream it plays on past the whistle to upstream's last sample, and
do_nothing's players, their rest to the whistle over, held every such game for 5 s; nor a rest the
whistle cut short, in the next game."""

from __future__ import annotations

import asyncio

from pillagerbench.rundir import spoiled
from pillagerbench.scenarios.mushroom_war import MushroomWarMaster
from pillagerbench.teams.base import Team
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


class GivesUp(Passive):
    """A team whose play fails at once: its players never run."""

    async def play(self, ctx) -> None:
        raise RuntimeError("this team gives up")


async def test_a_team_whose_play_is_over_holds_nothing_past_the_whistle(tmp_path):
    (rec,) = await play_series(
        "mushroom_war", "do_nothing", GivesUp(), tmp_path, length=5, clock="lockstep", scoring="upstream"
    )
    assert rec.status == "ok", rec.error
    assert rec.scores["upstream"] == {"red": 0.0, "blue": 0.0}
    assert (tmp_path / "episode_000" / "play-blue.error.txt").read_text().startswith("RuntimeError")
    assert_no_wall_clock_waits(tmp_path / "server.log")


async def test_a_rest_the_whistle_cut_short_gives_nothing_back_in_the_next_game(tmp_path):
    """protocol=upstream waits 4 s of game time after each run: the whistle cuts the last one short, and
    its tick, reached in the next game, held that game's players idle until the server let go."""
    recs = await play_series(
        "mushroom_war", "do_nothing", "balanced", tmp_path, episodes=2, length=10, clock="lockstep",
        protocol="upstream", scoring="upstream",
    )  # fmt: skip
    assert [r.status for r in recs] == ["ok", "ok"], [r.error for r in recs]
    assert all(r.runs for r in recs), [r.runs for r in recs]
    assert_no_wall_clock_waits(tmp_path / "server.log")


class WaitsOnTheWall(Team):
    """Runs one player once, then waits on the wall clock: neither runs nor rests its players."""

    name = "waits_on_the_wall"

    async def play(self, ctx) -> None:
        await next(iter(ctx.players.values())).run("await bot.waitForTicks(5)")
        await asyncio.sleep(3600)


async def test_a_world_that_went_on_without_an_idle_player_is_in_the_record(tmp_path):
    """The game went on at a tick the wall clock chose: stalled, spoiled on our side (rundir/faults.py; a
    series plays another episode in its place: tests/experiments/test_stalled.py), no team's problem."""
    (rec,) = await play_series(
        "mushroom_war", WaitsOnTheWall(), "do_nothing", tmp_path, length=5, clock="lockstep", idle_limit_s=0.5
    )
    assert rec.status == "ok", rec.error
    assert rec.stalled and spoiled(rec) == "stalled", rec.stall_reason
    went_on = [r for r in str(rec.stall_reason).split("; ") if r.startswith("lockstep: ")]
    assert len(went_on) == 2, rec.stall_reason  # both players: one after its run, one never run
    assert all("went on without it" in r and "(1x)" in r for r in went_on), went_on
    assert rec.problems == {}, rec.problems
    assert "let go after 500 ms" in (tmp_path / "server.log").read_text()


class ThinksLong(Team):
    """Rests one player to the whistle, runs the other once, then holds the world itself for 2 s of wall time
    (as an LLM's call in flight), then rests it too."""

    name = "thinks_long"

    async def play(self, ctx) -> None:
        first, second = ctx.players.values()
        rest = asyncio.create_task(ctx.sleep(ctx.time_left(), second.name))
        await first.run("await bot.waitForTicks(5)")
        async with ctx.clock.thinking(ctx.side.key):
            await asyncio.sleep(2)
        await ctx.sleep(ctx.time_left(), first.name)
        await rest


async def test_a_let_go_while_the_team_held_the_world_is_its_own_not_a_stall(tmp_path):
    """The team's own hold (its call in flight) held the world past the server's limit on its idle bot: the
    world did not go on at the limit, and once the call ended it went on at a moment the call chose."""
    (rec,) = await play_series(
        "mushroom_war", ThinksLong(), "do_nothing", tmp_path, length=5, clock="lockstep", idle_limit_s=0.5
    )
    assert rec.status == "ok", rec.error
    assert not rec.stalled and spoiled(rec) is None, rec.stall_reason
    (own,) = rec.problems["red"]
    assert own.startswith("lockstep: Ryn idle while its team held the world past") and "(1x)" in own, own
    assert "let go after 500 ms" in (tmp_path / "server.log").read_text()


class OneRestsOneRuns(Team):
    """One player rests to the whistle, its loop then over; the other runs on past it."""

    name = "one_rests_one_runs"

    async def play(self, ctx) -> None:
        first, second = ctx.players.values()

        async def rests():
            await first.run("await bot.waitForTicks(5)")
            await ctx.sleep(ctx.time_left(), first.name)

        await asyncio.gather(rests(), second.run("while (true) await bot.waitForTicks(1)"))


async def test_past_the_whistle_no_player_holds_the_world(tmp_path):
    """With scoring=upstream the game plays on past the whistle; a player whose rest ended there (its
    team's play not over: the other player runs on) held the world until the server let go of it."""
    (rec,) = await play_series(
        "mushroom_war", OneRestsOneRuns(), "do_nothing", tmp_path, length=5, clock="lockstep", scoring="upstream",
        idle_limit_s=0.5,
    )  # fmt: skip
    assert rec.status == "ok", rec.error
    assert rec.problems == {} and not rec.stalled, (rec.problems, rec.stall_reason)
    assert_no_wall_clock_waits(tmp_path / "server.log")


async def test_the_score_at_the_whistle_is_taken_at_its_tick(tmp_path, monkeypatch):
    """On the lockstep clock the world is held at the whistle's tick until its score is taken: taken while
    the world went on, it counted what the ticks Python took on the wall clock brought. Both scorings."""
    ticks: list[int] = []
    stock = MushroomWarMaster.scores

    async def scores(self):
        ticks.append((await self.server.clock())["tick"])
        return await stock(self)

    monkeypatch.setattr(MushroomWarMaster, "scores", scores)
    for scoring in ("clean", "upstream"):
        ticks.clear()
        (rec,) = await play_series(
            "mushroom_war", "do_nothing", "balanced", tmp_path / scoring, length=4, clock="lockstep", scoring=scoring
        )
        assert rec.status == "ok", rec.error
        # one sample a second from the game's first tick (0 to 3 s), then the whistle's at 4 s exactly
        assert ticks[:5] == [ticks[0] + 20 * t for t in range(5)], (scoring, ticks)


def assert_no_wall_clock_waits(server_log) -> None:
    log = server_log.read_text()
    assert "let go after" not in log, [line for line in log.splitlines() if "let go after" in line]
