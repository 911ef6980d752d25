"""Block drops, tilling, planting, growth and harvest, with real bots where a player acts."""

from __future__ import annotations

import asyncio
import contextlib

from tests.arena.conftest import count, held_or_on_ground

DIG = """
const b = bot.blockAt(new Vec3(%d, %d, %d))
if (!b || b.name === 'air') throw new Error('nothing to dig at ' + JSON.stringify([%d, %d, %d]) + ': ' + (b && b.name))
await bot.dig(b, true)
await sleep(900)   // drops are picked up after a short delay
"""


async def block(arena, pos):
    return await arena.request("get_block", pos=pos)


@contextlib.asynccontextmanager
async def fast_growth(arena, tps=100, chance=1.0):
    await arena.request("tick_rate", tps=tps)
    await arena.request("crop_growth", chance=chance)
    try:
        yield
    finally:
        await arena.request("tick_rate", tps=20)
        await arena.request("crop_growth", chance=0.0)


async def wait_block(arena, pos, predicate, timeout=10.0):
    for _ in range(int(timeout / 0.1)):
        b = await block(arena, pos)
        if predicate(b):
            return b
        await asyncio.sleep(0.1)
    raise AssertionError(f"block at {pos} never matched; last {b}")


async def test_mushroom_blocks_drop_0_to_2_and_slime_drops_itself(arena, bots, area):
    alice, _ = bots
    cells = [area.at(3 + i % 3, 4, 1 + i // 3) for i in range(6)]
    await arena.request(
        "set_blocks", blocks=[[*c, "red_mushroom_block"] for c in cells] + [[*area.at(1, 4, 4), "slime_block"]]
    )
    await area.put(alice, 2, 2)
    q = arena.control.subscribe()
    try:
        for c in cells + [area.at(1, 4, 4)]:
            await alice.eval(DIG % (*c, *c))
        await asyncio.sleep(0.5)
        events = [e for e in (q.get_nowait() for _ in range(q.qsize())) if e["event"] == "block_dug"]
    finally:
        arena.control.unsubscribe(q)
    mush = [e for e in events if e["block"] == "red_mushroom_block"]
    assert len(mush) == 6
    dropped = sum(n for e in mush for name, n in e["drops"])
    assert all(sum(n for _, n in e["drops"]) <= 2 for e in mush)
    assert await held_or_on_ground(arena, "alice", "red_mushroom") == dropped
    assert await held_or_on_ground(arena, "alice", "slime_block") == 1
    assert (await block(arena, cells[0]))["name"] == "air"


async def test_hoe_tills_seeds_grow_and_ripe_wheat_drops_wheat_and_seeds(arena, bots, area):
    alice, _ = bots
    soil = area.at(3, 3, 2)
    await area.put(alice, 2, 2, {"wooden_hoe": 1, "wheat_seeds": 2})
    await alice.eval(
        """
        await bot.equip(mcData.itemsByName.wooden_hoe.id, 'hand')
        await bot.activateBlock(bot.blockAt(new Vec3(%d, %d, %d)))
        await sleep(300)
    """
        % tuple(soil)
    )
    assert (await block(arena, soil))["name"] == "farmland"
    await alice.eval(
        """
        await bot.equip(mcData.itemsByName.wheat_seeds.id, 'hand')
        await bot.placeBlock(bot.blockAt(new Vec3(%d, %d, %d)), new Vec3(0, 1, 0))
        await sleep(300)
    """
        % tuple(soil)
    )
    crop = [soil[0], 4, soil[2]]
    assert await block(arena, crop) == {
        "name": "wheat",
        "properties": {"age": 0},
        "state": (await block(arena, crop))["state"],
    }
    assert await count(arena, "alice", "wheat_seeds") == 1
    async with fast_growth(arena):
        await wait_block(arena, crop, lambda b: b["properties"].get("age") == 7)
    await alice.eval(DIG % (*crop, *crop))
    assert await held_or_on_ground(arena, "alice", "wheat") == 1
    assert 1 <= await held_or_on_ground(arena, "alice", "wheat_seeds") <= 4


async def test_young_crops_drop_only_a_seed(arena, bots, area):
    alice, _ = bots
    crop = area.at(3, 4, 2)
    await arena.request("set_blocks", blocks=[[*area.at(3, 3, 2), "farmland"], [*crop, "beetroots", {"age": 1}]])
    await area.put(alice, 2, 2)
    await alice.eval(DIG % (*crop, *crop))
    assert await held_or_on_ground(arena, "alice", "beetroot_seeds") == 1
    assert await held_or_on_ground(arena, "alice", "beetroot") == 0


async def test_seeds_refuse_to_grow_off_farmland(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 2, 2, {"carrot": 1})
    target = area.at(3, 3, 2)  # grass, not farmland
    await alice.eval(
        """
        await bot.equip(mcData.itemsByName.carrot.id, 'hand')
        await bot.placeBlock(bot.blockAt(new Vec3(%d, %d, %d)), new Vec3(0, 1, 0)).catch(() => {})
        await sleep(300)
    """
        % tuple(target)
    )
    assert (await block(arena, [target[0], 4, target[2]]))["name"] == "air"
    assert await count(arena, "alice", "carrot") == 1


async def test_stems_grow_fruit_and_sugar_cane_grows_three_high(arena, bots, area):
    stem = area.at(3, 4, 3)
    cane = area.at(8, 4, 3)
    await arena.request("fill", **{"from": area.at(2, 3, 2), "to": area.at(4, 3, 4), "block": "farmland"})
    await arena.request("set_blocks", blocks=[[*stem, "melon_stem", {"age": 6}], [*cane, "sugar_cane"]])
    async with fast_growth(arena):
        await wait_block(arena, stem, lambda b: b["name"] == "attached_melon_stem", timeout=15)
        await wait_block(arena, [cane[0], 6, cane[2]], lambda b: b["name"] == "sugar_cane", timeout=15)
        await asyncio.sleep(1.0)
    facing = (await block(arena, stem))["properties"]["facing"]
    dx, dz = {"east": (1, 0), "west": (-1, 0), "south": (0, 1), "north": (0, -1)}[facing]
    assert (await block(arena, [stem[0] + dx, 4, stem[2] + dz]))["name"] == "melon"
    assert (await block(arena, [cane[0], 7, cane[2]]))["name"] == "air"  # at most 3 high


async def test_cocoa_on_jungle_log_and_sweet_berries_by_right_click(arena, bots, area):
    alice, _ = bots
    log = area.at(4, 4, 2)
    bush = area.at(2, 4, 3)
    await arena.request("set_blocks", blocks=[[*log, "jungle_log"], [*bush, "sweet_berry_bush", {"age": 3}]])
    await area.put(alice, 2, 2, {"cocoa_beans": 1})
    await alice.eval(
        """
        await bot.equip(mcData.itemsByName.cocoa_beans.id, 'hand')
        await bot.placeBlock(bot.blockAt(new Vec3(%d, %d, %d)), new Vec3(-1, 0, 0))
        await sleep(300)
    """
        % tuple(log)
    )
    cocoa = await block(arena, [log[0] - 1, 4, log[2]])
    assert cocoa["name"] == "cocoa" and cocoa["properties"]["facing"] == "east"
    await alice.eval(
        """
        await bot.activateBlock(bot.blockAt(new Vec3(%d, %d, %d)))
        await sleep(1200)
    """
        % tuple(bush)
    )
    assert (await block(arena, bush))["properties"]["age"] == 1
    assert 2 <= await held_or_on_ground(arena, "alice", "sweet_berries") <= 3
