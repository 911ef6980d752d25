"""Thinking on the lockstep clock, on the real server: an LLM answer that takes 3 s of wall time costs
no game time (the world waits for it), and `clock.ticks_per_1k_tokens` charges a set amount instead."""

from __future__ import annotations

import asyncio
import time

import pytest_asyncio

from pillagerbench.llm.fake_server import Rule
from pillagerbench.server import ArenaServer
from pillagerbench.server.clock import LockstepClock, RealClock
from tests.support.llm import llm_client_fixture

llm_client = llm_client_fixture()


@pytest_asyncio.fixture(loop_scope="session")
async def lockstep():
    server = ArenaServer(crop_growth_chance=0.0, clock="lockstep")
    await server.start()
    await server.clock(unpaced=True)  # with nothing held the clock runs far faster than real time
    yield server
    await server.stop()


class Ticks:
    """The server, keeping the tick each hold and release answered (where the clock stood then)."""

    def __init__(self, server: ArenaServer):
        self.server, self.held, self.released = server, [], []

    def __getattr__(self, name):
        return getattr(self.server, name)

    async def hold(self, who: str) -> int:
        self.held.append(await self.server.hold(who))
        return self.held[-1]

    async def release(self, who: str) -> int:
        self.released.append(await self.server.release(who))
        return self.released[-1]


async def test_an_answer_3_s_late_costs_no_tick_and_the_clock_runs_on_after(lockstep, fake_llm, llm_client):
    fake_llm.add(Rule(reply="fine", delay=3.0))
    ticks = Ticks(lockstep)
    clock = await LockstepClock(ticks, lockstep.control).start()
    llm = llm_client("red")
    llm.thinking.during_game(lambda: clock.thinking("red"), lambda tokens: clock.charge(tokens, []))

    async def ticks_during_the_call() -> tuple[int, int]:  # the server's own tick, read while the answer is awaited
        await asyncio.sleep(0.5)
        early = (await lockstep.clock())["tick"]
        await asyncio.sleep(2.0)
        return early, (await lockstep.clock())["tick"]

    started = time.monotonic()
    during = asyncio.create_task(ticks_during_the_call())
    answer = await llm.complete("hello", role="action")
    assert answer.text == "fine" and time.monotonic() - started >= 3.0
    early, late = await during
    assert early == late, f"the world ran {late - early} ticks during the call (unpaced, nothing else holds it)"
    assert early - ticks.held[0] <= 1  # held from the call's start, not from some moment after it
    assert len(ticks.held) == len(ticks.released) == 1
    assert ticks.released[0] - ticks.held[0] <= 1, f"the call cost {ticks.released[0] - ticks.held[0]} ticks"
    after = ticks.released[0]
    await clock.sleep(1.0)
    assert (await lockstep.clock())["tick"] >= after + 20  # released: the world goes on
    await clock.close()


async def test_thinking_charged_per_token_costs_that_many_ticks(lockstep, fake_llm, llm_client):
    fake_llm.add(Rule(reply="word " * 200))
    clock = await LockstepClock(lockstep, lockstep.control, ticks_per_1k_tokens=100).start()
    llm = llm_client("red")
    llm.thinking.during_game(lambda: clock.thinking("red"), lambda tokens: clock.charge(tokens, []))
    before = (await lockstep.clock())["tick"]
    answer = await llm.complete("hello", role="action")
    charged = answer.output_tokens / 1000 * 100
    assert answer.output_tokens > 100
    assert (await lockstep.clock())["tick"] - before >= charged  # waited that game time before returning
    llm.thinking.after_game()
    before = (await lockstep.clock())["tick"]
    await llm.complete("hello", role="action")  # after the game: a call is just a call
    await clock.close()


async def test_the_real_clock_neither_holds_nor_charges():
    clock = RealClock()
    async with clock.thinking("red"):
        pass
    started = time.monotonic()
    await clock.charge(10_000, ["Ryn"])
    async with clock.at(time.monotonic() + 0.2, "game-master"):
        assert time.monotonic() - started >= 0.19
