"""One arena server per test module; each test gets its own patch of ground and its own players
(`make_player`; a module may share players between tests that leave them as they were: `start_player`)."""

from __future__ import annotations

import itertools

import pytest_asyncio

from pillagerbench.players import Player
from pillagerbench.server import ArenaServer
from tests.support.llm import fake_llm  # noqa: F401 - a fixture (test_lockstep_thinking.py)

_area_ids = itertools.count(1)
_names = itertools.count(1)


@pytest_asyncio.fixture(scope="module", loop_scope="session")
async def server():
    srv = ArenaServer(crop_growth_chance=0.0)
    await srv.start()
    yield srv
    await srv.stop()


class Area:
    """Ground at x in [x0, x0 + 16), z in [-8, 8) (other areas are 80 blocks away); players stand at y = 4."""

    def __init__(self, server: ArenaServer):
        self.server = server
        self.x0 = 80 * next(_area_ids)

    def at(self, dx: float, y: float, dz: float) -> list[float]:
        return [self.x0 + dx, y, dz]

    async def blocks(self, *blocks):
        """set_blocks with x relative to the area: (dx, y, z, name[, props])."""
        await self.server.set_blocks(blocks=[[self.x0 + b[0], *b[1:]] for b in blocks])


@pytest_asyncio.fixture(loop_scope="session")
async def area(server):
    return Area(server)


@pytest_asyncio.fixture(loop_scope="session")
async def make_player(server, tmp_path):
    """make_player(dx, dz, inventory) -> a started Player standing in the test's area."""
    made: list[Player] = []

    async def make(area: Area, dx: float = 0, dz: float = 0, inventory: dict | None = None, **kw) -> Player:
        return await start_player(server, area, tmp_path / "logs", made, dx, dz, inventory, **kw)

    yield make
    await close_players(server, made)


async def start_player(
    server: ArenaServer, area: Area, log_dir, made: list[Player], dx: float = 0, dz: float = 0, inventory=None, **kw
) -> Player:
    """A started Player (a new name) standing at (dx, dz) of `area` with `inventory`, added to `made`."""
    p = Player(f"t{next(_names)}", server.port, server=server, log_dir=log_dir, **kw)
    await p.start()
    made.append(p)
    await p.reset(position=area.at(dx, 4, dz), inventory=inventory or {})
    return p


async def close_players(server: ArenaServer, made: list[Player]) -> None:
    for p in made:
        await p.close()
    # Mobs left in the world make later logins fail (server bug, see docs/players.md): remove them.
    await server.remove_entities()


async def count(server: ArenaServer, player: str, item: str) -> int:
    """How many of `item` the server says the player holds."""
    return sum(s["count"] for s in await server.inventory(player=player) if s["name"] == item)
