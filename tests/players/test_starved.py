"""A bot silent past its watchdog (1 s without a heartbeat) is restarted either way; what it is blamed on
is told by the CPU time its process got meanwhile (players/bot_process.py): a bot the machine stopped
(SIGSTOP here, as a starved machine would leave it) got none and was starved, the machine's fault (kept
in `stalls`: the match spoils the episode), while agent code in an endless loop burns its core and is
still the code's. On both clocks, with real bots on the real server."""

from __future__ import annotations

import asyncio
import itertools
import os
import signal
import time

import pytest_asyncio

from pillagerbench.players.events import errors
from pillagerbench.players.player import Player
from pillagerbench.server import ArenaServer
from tests.players.conftest import Area

_names = itertools.count()
LONG_WAIT = "bot.chat('waiting'); await bot.waitForTicks(1000000)"


@pytest_asyncio.fixture(scope="module", loop_scope="session", params=["real", "lockstep"])
async def world(request, tmp_path_factory):
    """(server, player) on one clock; the lockstep one unpaced."""
    server = ArenaServer(crop_growth_chance=0.0, clock=request.param)
    await server.start()
    logs = tmp_path_factory.mktemp("logs")
    player = Player(f"sv{next(_names)}", server.port, server=server, log_dir=logs, clock=request.param)
    await player.start()
    await player.reset(position=Area(server).at(0, 4, 0), inventory={})
    if request.param == "lockstep":
        await server.clock(unpaced=True)
    yield server, player
    await player.close()
    await server.stop()


async def stopped_for(player: Player, seconds: float) -> list:
    """A long run, its bot process stopped by a signal for `seconds` as soon as it runs, then let go on."""
    running = asyncio.Event()
    run = asyncio.create_task(player.run(LONG_WAIT, on_event=lambda e: running.set()))
    await asyncio.wait_for(running.wait(), 20)
    pid = player.bot.proc.pid if player.bot.proc else 0
    os.kill(pid, signal.SIGSTOP)
    t0 = time.monotonic()
    try:
        events = await asyncio.wait_for(asyncio.shield(run), 30)  # the watchdog ends it (1 s, then a login)
    finally:
        await asyncio.sleep(max(0.0, seconds - (time.monotonic() - t0)))
        try:
            os.kill(pid, signal.SIGCONT)  # (killed by the restart already: nothing to go on)
        except ProcessLookupError:
            pass
    return events


async def test_a_bot_the_machine_stopped_was_starved_not_looping(world):
    _, player = world
    restarts = player.bot.restarts
    player.bot.watchdog.take_stalls()
    events = await stopped_for(player, 3.0)
    (err,) = errors(events)
    assert "starved of CPU" in err and "not the code's" in err and "endless loop" not in err, err
    assert player.bot.restarts == restarts + 1 and player.bot.alive
    (stall,) = player.bot.watchdog.take_stalls()
    assert stall.startswith(f"{player.name} was starved of CPU for ") and "restarted" in stall, stall
    assert player.bot.watchdog.take_stalls() == []  # taken once


async def test_an_endless_loop_is_still_the_codes(world):
    _, player = world
    restarts = player.bot.restarts
    player.bot.watchdog.take_stalls()
    events = await player.run("await bot.waitForTicks(1)\nwhile (true) {}")
    (err,) = errors(events)
    assert "blocked the bot" in err and "an endless loop?" in err, err
    assert player.bot.restarts == restarts + 1 and player.bot.alive
    assert player.bot.watchdog.take_stalls() == []  # the code's: no stall of ours


async def test_a_bot_that_did_not_stop_in_time_is_a_stall(world):
    """A bot told to stop that does not within 2 s is restarted, a stall of ours: the bot is ours, and a team's
    loop is caught before by the watchdog (here turned off, so that the stop's own limit is what acts)."""
    _, player = world
    player.bot.watchdog.take_stalls()
    running = asyncio.Event()
    run = asyncio.create_task(player.run(LONG_WAIT, on_event=lambda e: running.set()))
    await asyncio.wait_for(running.wait(), 20)
    watchdog, player.bot.watchdog_s = player.bot.watchdog_s, 60.0
    try:
        assert player.bot.proc is not None
        os.kill(player.bot.proc.pid, signal.SIGSTOP)  # (its restart kills it)
        await player.stop()
    finally:
        player.bot.watchdog_s = watchdog
    events = await asyncio.wait_for(run, 30)
    assert errors(events) == ["Error: the bot did not stop within 2 s and was restarted"], errors(events)
    assert player.bot.watchdog.take_stalls() == [f"{player.name} did not stop within 2 s and was restarted"]
    assert player.bot.alive
