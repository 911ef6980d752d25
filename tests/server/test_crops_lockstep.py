"""On the lockstep clock crops grow during games only: how many ticks passed between the arena's build
and the game (between games the clock keeps real time's pace, so the wall clock chooses that number)
changes neither a crop's age at the game's start nor its ages in the game. On the real clock crops grow
whenever the server ticks (tests/server/test_farming.py)."""

from __future__ import annotations

from pillagerbench.server import ArenaServer
from tests.support.server_clock import wait_ticks

BUSHES = [[40 + 2 * i, 4, 8] for i in range(6)]


async def ages_by_tick(server, seed: int, before: int) -> tuple[list[int], list[list[int]]]:
    """Bushes planted anew; their ages after `before` ticks with no game; then their ages every 20 ticks
    of its first 200."""
    await server.clock(game=False, speed=1)  # between games: real time's pace
    await server.seed(seed)
    await server.set_blocks(blocks=[[*p, "sweet_berry_bush", {"age": 0}] for p in BUSHES])

    async def ages() -> list[int]:
        return [int((await server.get_block(pos=p))["properties"]["age"]) for p in BUSHES]

    await wait_ticks(server, before)
    pre_game = await ages()
    start = (await server.clock(game=True, speed=0.2))["tick"]  # the game's first tick, 250 ms to hold the next
    assert await server.wait_tick(start + 1, hold="test") == start + 1
    await server.clock(unpaced=True)  # from here on each wait is in place before the last hold goes
    seen = []
    for t in range(start + 20, start + 201, 20):  # each held while the bushes are read
        assert await server.wait_tick(t, hold="test", release="test") == t
        seen.append(await ages())
    await server.release("test")
    return pre_game, seen


async def test_on_the_lockstep_clock_crops_grow_in_games_only_and_the_seed_decides_how(tmp_path):
    async with ArenaServer(log_path=tmp_path / "server.log", clock="lockstep") as server:
        await server.crop_growth(chance=0.0, random_tick_speed=200)  # vanilla's rule, fast: a step in seconds
        short = await ages_by_tick(server, seed=3, before=5)
        long = await ages_by_tick(server, seed=3, before=80)
        other = await ages_by_tick(server, seed=4, before=5)
    assert short[0] == long[0] == [0] * len(BUSHES)  # nothing grew before the game, however long it waited
    assert sum(short[1][-1]) > 0  # they grow in the game
    assert short[1] == long[1]  # the same ages at the same ticks of the game
    assert other[1] != short[1]  # the seed decides
