"""One arena server and two real mineflayer bots (alice, bob) for the whole set of tests/server modules.

Each test gets its own area of the world and resets the bots' inventories through the control
channel, so tests stay independent while paying for one server start and two logins.
"""

from __future__ import annotations

import asyncio

import pytest_asyncio

from pillagerbench.server import ArenaServer
from tests.support.bots import TestBot


@pytest_asyncio.fixture(scope="session", loop_scope="session")
async def arena():
    server = ArenaServer(crop_growth_chance=0.0)
    await server.start()
    yield server
    await server.stop()


@pytest_asyncio.fixture(scope="session", loop_scope="session")
async def bots(arena):
    alice = await TestBot(arena.port, "alice").start()
    await asyncio.sleep(0.3)  # flying-squid handles one login at a time best
    bob = await TestBot(arena.port, "bob").start()
    yield alice, bob
    await alice.stop()
    await bob.stop()


class Area:
    """A fresh patch of ground for one test: x in [x0, x0+16), z in [0, 16)."""

    _next = 0

    def __init__(self, arena: ArenaServer):
        Area._next += 1
        self.arena = arena
        self.x0 = 32 * Area._next

    def at(self, dx: float, dy: float, dz: float) -> list[float]:
        return [self.x0 + dx, dy, dz]

    async def set_block(self, pos: list[float], block: str, seen_by: TestBot):
        """Set a block and wait until `seen_by` sees it: mineflayer plans a dig (how long it takes) from
        the block it sees, and the block update reaches it a tick or more after the server changed it."""
        await self.arena.set_block(pos=pos, block=block)
        await seen_by.eval(
            "const at = new Vec3(%d, %d, %d)\n"
            "for (let i = 0; bot.blockAt(at)?.name !== '%s'; i++) {"
            " if (i > 100) throw new Error('the bot never saw the block'); await sleep(50) }" % (*pos, block)
        )

    async def put(self, bot: TestBot, dx: float, dz: float, items: dict[str, int] | None = None):
        """Teleport a bot onto the ground at (dx, dz), give it exactly `items`, wait until it sees the chunk."""
        await self.arena.set_inventory(player=bot.username, items=items or {})
        await self.arena.teleport(player=bot.username, pos=self.at(dx + 0.5, 4, dz + 0.5))
        await bot.eval(
            "for (let i = 0; ; i++) { const b = bot.blockAt(bot.entity.position.offset(0, -1, 0));"
            " if (b && b.name !== 'air' && bot.entity.position.distanceTo(new Vec3(%f, 4, %f)) < 1) return;"
            " if (i > 100) throw new Error('no ground after teleport: ' + bot.entity.position); await sleep(50) }"
            % (self.x0 + dx + 0.5, dz + 0.5)
        )


@pytest_asyncio.fixture(loop_scope="session")
async def area(arena):
    return Area(arena)


async def count(arena: ArenaServer, player: str, item: str) -> int:
    """How many of `item` the server says the player holds."""
    return sum(s["count"] for s in await arena.inventory(player=player) if s["name"] == item)


async def on_ground(arena: ArenaServer, item: str, near: list[float] | None = None, radius: float = 4.0) -> int:
    """`item`s lying in the world; with `near`, only those within `radius` blocks of it (other tests
    leave items elsewhere in the shared world)."""
    return sum(
        i["count"]
        for i in await arena.items()
        if i["item"] == item and (near is None or sum((a - b) ** 2 for a, b in zip(i["pos"], near)) < radius**2)
    )


async def held_or_on_ground(arena: ArenaServer, player: str, item: str) -> int:
    """`item`s the player holds plus those lying in the world: what a drop made, whether or not the
    player has picked it up yet (pickup waits for the item's delay and the server's next pass)."""
    return await count(arena, player, item) + await on_ground(arena, item)


async def wait_until(predicate, timeout: float = 8.0, step: float = 0.1) -> bool:
    """Poll an async predicate until it holds (True) or `timeout` seconds pass (False)."""
    deadline = asyncio.get_running_loop().time() + timeout
    while asyncio.get_running_loop().time() < deadline:
        if await predicate():
            return True
        await asyncio.sleep(step)
    return False


async def equals(coro, value) -> bool:
    return (await coro) == value
