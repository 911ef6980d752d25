"""A game our machine stalled is spoiled on our side and played again (rundir/faults.py `stalled`, like a
lagged real-clock episode): on the lockstep clock the world went on without an idle bot at the server's
wall-clock limit, or a bot was restarted for the machine's sake (stopped: starved of CPU, not looping).
The record says why, a series plays another index in its place, and the report's Failures table lists it.
Real server and bots on loopback, the lockstep clock, the server's wall-clock limit shortened to 0.5 s.
"""

from __future__ import annotations

import asyncio
import os
import signal

import pandas as pd
import pytest

from pillagerbench.config.compose import load_config
from pillagerbench.config.schema import RunConfig
from pillagerbench.experiments.series import run_series
from pillagerbench.metrics.faults import fault_note
from pillagerbench.metrics.verified import load_runs
from pillagerbench.players.events import errors
from pillagerbench.report.build import build_report
from pillagerbench.rundir import RunDir, SeriesSpec, faults, progress, spoiled
from pillagerbench.scenarios import make_scenario
from pillagerbench.server import ArenaServer
from pillagerbench.teams.do_nothing import DoNothing
from tests.teams.conftest import play_series

TEAM = "tests.experiments.test_stalled:StallsOnce"


class StallsOnce(DoNothing):
    """In its first episode, neither runs nor rests its players (it waits on the wall clock): the server lets
    go of their idle bots at its wall-clock limit. Then it does nothing, as do_nothing does."""

    name = "stalls_once"

    async def play(self, ctx) -> None:
        if ctx.episode == 0:
            await asyncio.sleep(3600)  # (cancelled at the whistle)
        await super().play(ctx)


@pytest.fixture
def short_idle_limit(monkeypatch):
    """The series' server lets go of an idle bot after 0.5 s of wall time (5 s in play)."""
    stock = ArenaServer.from_config.__func__

    def from_config(cls, *args, **kwargs):
        server = stock(cls, *args, **kwargs)
        server.settings["idleLimitMs"] = 500
        return server

    monkeypatch.setattr(ArenaServer, "from_config", classmethod(from_config))


async def test_a_world_that_went_on_without_a_bot_is_spoiled_and_played_again(tmp_path, short_idle_limit):
    cfg = load_config(
        [
            "scenario=mushroom_war",
            f"red={TEAM}",
            "blue=do_nothing",
            "episode_length=3",
            "clock=lockstep",
            "episodes=1",
            "retries=1",
        ]
    )
    spec = SeriesSpec("run", 0, "run", "mushroom_war", TEAM, "do_nothing", TEAM, "do_nothing", 1, 0, RunConfig.of(cfg))
    await run_series(spec, tmp_path / "run", say=lambda _: None)
    records = RunDir(tmp_path / "run").finished()
    assert sorted(records) == [0, 1], records  # the stalled episode 0, then index 1 in its place
    stalled = records[0]
    assert stalled.status == "ok" and stalled.stalled and spoiled(stalled) == "stalled"
    assert "went on without it after the server's wall-clock limit" in str(stalled.stall_reason)
    red = make_scenario("mushroom_war").side("red").player_names
    assert all(f"lockstep: {name} idle" in str(stalled.stall_reason) for name in red), stalled.stall_reason
    assert not records[1].stalled and not spoiled(records[1]), records[1].stall_reason
    assert [(f.whose, f.kind) for f in faults(stalled)] == [("harness", "stalled")]
    done = progress(records, 1, 1)
    assert (done.used, done.spoiled, done.given_up, done.complete) == (1, 1, 0, True)

    runs = load_runs([tmp_path / "run"])
    assert list(runs.episodes["episode"]) == [1] and list(runs.spoiled["episode"]) == [0]
    (note,) = fault_note(runs.faults)
    assert "ours (the harness) in 1 episode(s) (stalled 1)" in note, note
    out = build_report([tmp_path / "run"], tmp_path / "report", with_replays=False)
    failures = pd.read_csv(tmp_path / "report" / "faults.csv")
    assert failures[["whose", "kind", "episode"]].values.tolist() == [["harness", "stalled", 0]]
    assert "went on without it" in failures["what"].iloc[0]
    assert any("spoiled on our side" in why for _, why in out["skipped"])


class StopsItsBot(DoNothing):
    """Rests all its players but one, runs that one's long wait and stops its bot process (SIGSTOP), as a
    machine that starves it would: the world waits for it (lockstep) until the watchdog restarts it."""

    name = "stops_its_bot"

    def __init__(self) -> None:
        super().__init__()
        self.events: list = []
        self.stopped = ""  # the player whose bot it stopped

    async def play(self, ctx) -> None:
        handle, *others = ctx.players.values()
        self.stopped = handle.name
        rest = asyncio.create_task(ctx.clock.rest([p.name for p in others], ctx.time_left()))
        running = asyncio.Event()
        code = "bot.chat('waiting'); await bot.waitForTicks(100000)"
        run = asyncio.create_task(handle.run(code, on_event=lambda e: running.set()))
        await running.wait()
        os.kill(handle.bot.proc.pid, signal.SIGSTOP)  # (its restart kills it)
        self.events = await run
        await rest
        await super().play(ctx)


async def test_a_bot_the_machine_stopped_spoils_the_game_and_is_not_the_codes_fault(tmp_path):
    team = StopsItsBot()
    (rec,) = await play_series("mushroom_war", team, "do_nothing", tmp_path, length=3, clock="lockstep")
    assert rec.status == "ok", rec.error
    (err,) = errors(team.events)
    assert "starved of CPU" in err and "endless loop" not in err, err  # what the team was told
    assert rec.stalled and spoiled(rec) == "stalled", rec
    (reason,) = str(rec.stall_reason).split("; ")  # the restart alone: no bot was let go meanwhile
    assert reason.startswith(f"{team.stopped} was starved of CPU for ") and "restarted" in reason, reason
    assert rec.problems == {}, rec.problems  # no team's problem: ours
