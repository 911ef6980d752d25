"""On the lockstep clock hens lay during games only, each one's cycle under way drawn at the game's
first tick: how many ticks passed before the game (between games the clock keeps real time's pace, so
the wall clock chooses that number) changes neither whether a hen lays before the game nor when it
lays in it. On the real clock cycles run from the farm's setup (tests/server/test_mobs.py)."""

from __future__ import annotations

from pillagerbench.server import ArenaServer
from tests.support.server_clock import wait_ticks

CHEST = [40, 4, 8]


async def eggs_by_tick(tmp_path, seed: int, before: int) -> tuple[int, list[int]]:
    """Eggs in the chest after `before` ticks with no game; then the game tick of each egg laid in its first 60."""
    async with ArenaServer(
        log_path=tmp_path / f"server_{seed}_{before}.log", clock="lockstep", crop_growth_chance=0.0
    ) as server:
        await server.seed(seed)
        await server.set_blocks(blocks=[[*CHEST, "chest"]])
        for dx in (1.5, 2.5, 3.5):
            await server.summon(mob="chicken", pos=[CHEST[0] + dx, 4, CHEST[2] + 0.5])
        await server.egg_farm(chest=CHEST, interval_s=0.5)  # 10 to 20 ticks a cycle
        await wait_ticks(server, before)
        pre_game = (await server.get_chest(pos=CHEST)).get("egg", 0)
        start = (await server.clock(game=True))["tick"]  # the game's first tick
        laid, had, held = [], pre_game, None
        for t in range(start + 1, start + 61):  # each tick held while the chest is read: no tick slips by
            await server.wait_tick(t, hold="test", release=held)
            held = "test"
            got = (await server.get_chest(pos=CHEST)).get("egg", 0)
            laid += [t - start] * (got - had)
            had = got
        await server.release("test")
        return pre_game, laid


async def test_on_the_lockstep_clock_hens_lay_in_games_only_and_the_seed_decides_when(tmp_path):
    short = await eggs_by_tick(tmp_path, seed=3, before=5)
    long = await eggs_by_tick(tmp_path, seed=3, before=45)
    other = await eggs_by_tick(tmp_path, seed=4, before=5)
    assert short[0] == long[0] == 0  # nothing before the game, however long it waited
    assert len(short[1]) >= 6  # three hens, 60 ticks, a cycle of 10 to 20
    assert short[1] == long[1]  # the same ticks of the game
    assert other[1] != short[1]  # the seed decides
