"""The lockstep clock (clock=lockstep) beside the real one, on the real server with real bots: the same
waits and digs take the same ticks, a held clock does not move, and a busy loop is still stopped by
wall time while the clock goes on."""

from __future__ import annotations

import asyncio
import itertools
import math
import time

import pytest
import pytest_asyncio

from pillagerbench.players.events import chats_by, errors
from pillagerbench.players.player import Player
from pillagerbench.server import ArenaServer
from tests.players.conftest import Area

_names = itertools.count()
DIGS: dict[str, int] = {}  # clock -> ticks of the dig (the real clock's module runs first)

# Agent code that says how many physics ticks (the bot's 50 ms steps) the awaited call took.
COUNTING = (
    "let n = 0; const f = () => n++; bot.on('physicsTick', f);\n"
    "%s\n"
    "bot.removeListener('physicsTick', f); bot.chat('ticks ' + n)"
)


@pytest_asyncio.fixture(scope="module", loop_scope="session", params=["real", "lockstep"])
async def world(request, tmp_path_factory):
    """(server, player, area) on one clock; the lockstep one unpaced."""
    server = ArenaServer(crop_growth_chance=0.0, clock=request.param)
    await server.start()
    logs = tmp_path_factory.mktemp("logs")
    player = Player(f"ls{next(_names)}", server.port, server=server, log_dir=logs, clock=request.param)
    await player.start()
    area = Area(server)
    await player.reset(position=area.at(0, 4, 0), inventory={})
    if request.param == "lockstep":
        await server.clock(unpaced=True)
    yield server, player, area
    await player.close()
    await server.stop()


async def ticks_of(player: Player, call: str) -> int:
    events = await player.run(COUNTING % call, timeout=60)
    said = [c for c in chats_by(events, player.name) if c.startswith("ticks ")]
    assert said, f"no tick count in {events}"
    return int(said[-1].split()[1])


# Wait until the bot sees the dirt (the dig then looks at it at once: forceLook, no turn counted).
# (The sandbox has no `sleep`: this loop once called it, and when the dirt had not reached the bot yet
# the run ended at once with a ReferenceError; the dig then began on air and counted 0 ticks.)
SEEN_FACING_AWAY = (
    "const at = new Vec3(%d, 4, 0); for (let i = 0; bot.blockAt(at)?.name !== 'dirt'; i++) {"
    " if (i > 100) throw new Error('no dirt'); await bot.waitForTicks(1) }"
    " await bot.lookAt(at.offset(0.5, 0.5, 0.5), true); await bot.waitForTicks(2)"
)

# The dig, begun on the ground, its ticks counted from there (`n` is COUNTING's): mineflayer times a dig
# begun off the ground 5 times as long, as vanilla does. Once in CI a lockstep dig counted 75 ticks,
# 5 x 15: the bot was off the ground as it began. Outside a game the world runs on while Python is
# between two calls, and a position packet from the server sets onGround false until the bot's next
# physics step (which packet it was is not known: flying-squid re-sends the position once after a
# login, and a movement correction teleports).
DIG = (
    "for (let i = 0; !bot.entity.onGround; i++) {"
    " if (i > 100) throw new Error('not on the ground'); await bot.waitForTicks(1) }"
    " n = 0; await bot.dig(bot.blockAt(new Vec3(%d, 4, 0)), true)"
)


async def see_dirt(player: Player, x: int) -> None:
    events = await player.run(SEEN_FACING_AWAY % x)
    assert not errors(events), errors(events)


def near(clock: str, got: int, want: int) -> bool:
    """Exactly under lockstep; within a tick or two of timer jitter on the real clock."""
    return got == want if clock == "lockstep" else abs(got - want) <= 2


@pytest.mark.parametrize("call", ["await bot.waitForTicks(100)", "await new Promise(r => setTimeout(r, 5000))"])
async def test_waiting_100_ticks_or_5_seconds_takes_100_ticks(world, call):
    server, player, _ = world
    mode = (await server.clock())["mode"]
    started = time.monotonic()
    got = await ticks_of(player, call)
    assert near(mode, got, 100), f"{mode}: {got} ticks"
    if mode == "lockstep":  # unpaced: faster than the 5 s the wall clock would take
        assert time.monotonic() - started < 5


async def test_a_dig_takes_the_same_ticks(world):
    server, player, area = world
    mode = (await server.clock())["mode"]
    await area.blocks((1, 4, 0, "dirt"))
    await see_dirt(player, area.x0 + 1)
    got = await ticks_of(player, DIG % (area.x0 + 1))
    # dirt by hand: hardness 0.5 -> 0.75 s, 15 ticks (mineflayer's dig time; the real clock's timers may
    # land a tick early or late)
    if mode == "lockstep":  # on the real clock the server's dig-time check may refuse a finish that
        # timer jitter made early (fair play working); on the game clock it never does
        assert (await server.get_block(pos=area.at(1, 4, 0)))["name"] == "air", "the dig did not count"
    assert near(mode, got, 15), f"{mode}: {got} ticks"
    DIGS[mode] = got
    if mode == "lockstep":
        assert got == await _dig_again(server, player, area)  # to the tick, every time
        if "real" in DIGS:  # the real clock's timer jitter: a tick or two (near())
            assert near("real", DIGS["real"], got), DIGS


async def _dig_again(server: ArenaServer, player: Player, area: Area) -> int:
    await area.blocks((1, 4, 0, "dirt"))
    await see_dirt(player, area.x0 + 1)
    return await ticks_of(player, DIG % (area.x0 + 1))


async def test_a_held_clock_does_not_move(world):
    server, _, _ = world
    if (await server.clock())["mode"] == "real":
        with pytest.raises(Exception, match="needs clock=lockstep"):
            await server.hold("red")
        return
    before = await server.hold("red")
    await server.hold("red")  # counted: two holds need two releases
    await asyncio.sleep(1.0)
    await server.release("red")
    await asyncio.sleep(0.5)
    assert (await server.clock())["tick"] == before and (await server.clock())["holds"] == ["red"]
    await server.release("red")
    assert await server.wait_tick(before + 20) >= before + 20


async def test_a_busy_loop_is_stopped_by_wall_time_and_the_clock_goes_on(world):
    server, player, _ = world
    events = await player.run("while (true) {}", timeout=60)
    assert any("an endless loop?" in e for e in errors(events)), errors(events)
    tick = (await server.clock())["tick"]
    assert await ticks_of(player, "await bot.waitForTicks(10)") in (
        (10,) if (await server.clock())["mode"] == "lockstep" else range(8, 13)
    )
    assert (await server.clock())["tick"] > tick


async def test_a_rested_player_holds_the_clock_again_on_its_tick(world):
    server, player, _ = world
    if (await server.clock())["mode"] == "real":
        with pytest.raises(Exception, match="needs clock=lockstep"):
            await server.rest([player.name], 10)
        return
    tick = (await server.clock(game=True))["tick"]  # a game: every bot idle, holding the clock
    try:
        await asyncio.sleep(0.5)
        assert (await server.clock())["tick"] == tick
        assert await server.rest([player.name], 30) == tick + 30  # the hold goes, and is back 30 ticks on
        await asyncio.sleep(0.5)
        assert (await server.clock())["tick"] == tick + 30 and (await server.clock())["holds"] == [
            f"idle:{player.name}"
        ]
    finally:
        await server.clock(game=False, drop_holds=True)


async def test_agent_codes_date_and_chance_are_the_games(world):
    server, player, area = world
    lockstep = (await server.clock())["mode"] == "lockstep"
    events = await player.run(
        "const t = Date.now(); await new Promise(r => setTimeout(r, 5000)); bot.chat('ms ' + (Date.now() - t))"
    )
    ms = int([c for c in chats_by(events, player.name) if c.startswith("ms ")][-1].split()[1])
    assert (ms == 5000) if lockstep else (4000 < ms < 7000), ms
    draws = []
    for _ in range(2):  # the same episode seed, the same draws: the bot's and its agent code's
        await player.reset(position=area.at(0, 4, 0), inventory={}, seed=7)
        events = await player.run("bot.chat('r ' + [Math.random(), Math.random()].join(' '))")
        draws.append([c for c in chats_by(events, player.name) if c.startswith("r ")][-1])
    await player.reset(position=area.at(0, 4, 0), inventory={}, seed=8)
    events = await player.run("bot.chat('r ' + [Math.random(), Math.random()].join(' '))")
    assert draws[0] == draws[1] != [c for c in chats_by(events, player.name) if c.startswith("r ")][-1], draws


async def test_a_settle_waits_for_the_servers_teleport(world):
    """A settle answers only once a teleport the server forced has arrived since the last settle: a
    bot already standing at the target must not answer before the teleport (and the look it sets) has
    come, or a reset reads the look from before (this raced once in CI)."""
    server, player, area = world
    await player.reset(position=area.at(0, 4, 0))
    here = (await player.observe())[0][1]["status"]["position"]
    pos = [here["x"], here["y"], here["z"]]
    assert await player.channel.settle(pos, 0.5, wait=5) is not True  # no teleport since the reset's settle
    await server.teleport(player.name, pos, 0.0, 0.0)
    assert await player.channel.settle(pos, 3, wait=6) is True


async def test_a_reset_faces_a_lockstep_player_as_at_login(world):
    """The whistle stops a player on the wall clock, facing wherever that left it: on the lockstep clock
    each episode's reset turns it back to the look it logged in with (placement.LOGIN_LOOK), so a series'
    next episode does not begin from a look the machine chose. The real clock keeps the look."""
    server, player, area = world
    mode = (await server.clock())["mode"]
    await player.run("await bot.look(2, 0.5, true); await bot.waitForTicks(2)")
    status = (await player.reset(position=area.at(0, 4, 0)))[0][1]["status"]
    look = (status["yaw"], status["pitch"])
    if mode == "lockstep":
        assert look == (math.pi, 0), look  # notchian yaw 0 (mineflayer's yaw is pi minus it)
    else:  # as it was, to the server's byte-sized angle
        assert abs(look[0] - 2) < 0.05 and abs(look[1] - 0.5) < 0.05, look
