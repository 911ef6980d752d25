"""Test helpers on the arena server's own clock and order: its tick counter (the control op `status`)
and a round trip through a player's connection and the control channel.

Tick-counted behaviour (furnaces, egg farms, healing) is measured in server ticks, so a busy machine
that runs the server below 20 TPS does not fail it; wall time bounds only how long a test may wait.
"""

from __future__ import annotations

import asyncio
import itertools
import json
from collections.abc import Awaitable, Callable

_markers = itertools.count(1)


async def tick(server) -> int:
    """The server's tick counter (ticks run since it started)."""
    return (await server.status())["tick"]


async def wait_ticks(server, n: int, timeout: float = 60.0) -> int:
    """Wait until the server has run `n` more ticks; return the tick reached. Fails after `timeout`
    wall seconds (a server that stopped ticking)."""
    loop = asyncio.get_running_loop()
    start, deadline = await tick(server), loop.time() + timeout
    while (now := await tick(server)) < start + n:
        assert loop.time() < deadline, f"the server ran {now - start} of {n} ticks in {timeout} s"
        await asyncio.sleep(0.02)
    return now


async def caught_up(server, player: str, say: Callable[[str], Awaitable[object]], timeout: float = 30.0) -> None:
    """Return once the server has handled everything `player` sent before this call and the control
    channel has delivered what came of it (e.g. `refused` events) to every subscriber.

    `say(text)` must make the player chat `text`: the server handles a connection's packets in order,
    so when it pushes that chat on the control channel, it has handled the earlier packets. Two more
    ticks then let handlers still awaiting and per-tick checks finish, and the `status` reply comes
    after every event pushed before it."""
    marker = f"sync {next(_markers)}"
    q = server.control.subscribe()
    try:
        await say(marker)
        loop = asyncio.get_running_loop()
        deadline = loop.time() + timeout
        while True:
            e = await asyncio.wait_for(q.get(), max(0.01, deadline - loop.time()))
            if e.get("event") == "chat" and e.get("player") == player and e.get("message") == marker:
                break
            assert e.get("event") != "closed", e
    finally:
        server.control.unsubscribe(q)
    await wait_ticks(server, 2)


def chat_code(text: str) -> str:
    """JavaScript making a bot chat `text`."""
    return f"bot.chat({json.dumps(text)})"


def clock_of(mode: str):
    """A Match's clock for `mode`: lockstep as fast as the bots allow, or the real clock."""
    from pillagerbench.config.schema import ClockConfig

    return ClockConfig(mode=mode, speed="max" if mode == "lockstep" else 1.0)
