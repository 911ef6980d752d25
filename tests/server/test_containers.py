"""Furnaces and chests: server-side contents, persistence, pre-filling."""

from __future__ import annotations

import asyncio

from tests.server.conftest import count
from tests.support.server_clock import tick, wait_ticks

FIND = """
let block = null
for (let i = 0; i < 40 && !block; i++, await sleep(50)) block = bot.findBlock({ matching: mcData.blocksByName['%s'].id, maxDistance: 6 })
if (!block) throw new Error('no %s in sight')
"""


async def test_chest_prefilled_withdraw_deposit_and_persist(arena, bots, area):
    alice, bob = bots
    chest = area.at(3, 4, 2)
    await arena.set_block(pos=chest, block="chest")
    await arena.set_chest(pos=chest, items={"egg": 5, "wheat": 70})
    await area.put(alice, 2, 2, {"bread": 4})
    seen = await alice.eval(
        FIND % ("chest", "chest")
        + """
        const c = await bot.openContainer(block)
        const seen = c.containerItems().map(i => [i.name, i.count])
        await c.withdraw(mcData.itemsByName.egg.id, null, 3)
        await c.deposit(mcData.itemsByName.bread.id, null, 4)
        c.close()
        await sleep(200)
        return seen
    """
    )
    assert sorted(seen) == [["egg", 5], ["wheat", 6], ["wheat", 64]]
    assert await arena.get_chest(pos=chest) == {"egg": 2, "wheat": 70, "bread": 4}
    assert await count(arena, "alice", "egg") == 3
    assert await count(arena, "alice", "bread") == 0
    # another player opening it later sees the same contents
    await area.put(bob, 4, 2)
    seen_by_bob = await bob.eval(
        FIND % ("chest", "chest")
        + """
        const c = await bot.openContainer(block)
        const items = c.containerItems().map(i => [i.name, i.count])
        c.close()
        return items
    """
    )
    assert sorted(seen_by_bob) == [["bread", 4], ["egg", 2], ["wheat", 6], ["wheat", 64]]


async def test_forged_chest_click_gets_nothing(arena, bots, area):
    alice, _ = bots
    chest = area.at(3, 4, 2)
    await arena.set_block(pos=chest, block="chest")
    await arena.set_chest(pos=chest, items={"egg": 1})
    await area.put(alice, 2, 2)
    await alice.eval(
        FIND % ("chest", "chest")
        + """
        const c = await bot.openContainer(block)
        // claim that slot 5 of the chest holds 64 diamonds and take them
        bot._client.write('window_click', { windowId: c.id, slot: 5, mouseButton: 0, action: 77, mode: 0,
          item: { present: true, itemId: mcData.itemsByName.diamond.id, itemCount: 64 } })
        bot._client.write('window_click', { windowId: c.id, slot: 30, mouseButton: 0, action: 78, mode: 0, item: { present: false } })
        await sleep(300)
        c.close()
        await sleep(200)
    """
    )
    assert await count(arena, "alice", "diamond") == 0
    assert await arena.get_chest(pos=chest) == {"egg": 1}


async def test_furnace_smelts_potato_in_200_ticks_with_prefuel(arena, bots, area):
    alice, _ = bots
    furnace = area.at(3, 4, 2)
    await arena.set_block(pos=furnace, block="furnace")
    await arena.set_furnace(pos=furnace, fuel=["coal", 2])
    await area.put(alice, 2, 2, {"potato": 2})
    await alice.eval(
        FIND % ("furnace", "furnace")
        + """
        const f = await bot.openFurnace(block)
        await f.putInput(mcData.itemsByName.potato.id, null, 2)
        f.close()
    """
    )

    async def started_at() -> tuple[dict, int]:
        """The furnace and the tick its current item started cooking (progress is cook ticks / 200;
        a tick may pass between the two reads)."""
        state = await arena.get_furnace(pos=furnace)
        return state, await tick(arena) - round(state["progress"] * 200)

    loop = asyncio.get_running_loop()
    deadline = loop.time() + 60  # wall time only bounds the waits: the server counts ticks
    while not (state := await arena.get_furnace(pos=furnace))["burning"]:
        assert loop.time() < deadline, f"the furnace never lit: {state}"
        await asyncio.sleep(0.05)
    state, first_start = await started_at()
    assert state["input"] == ["potato", 2] and state["fuel"] == ["coal", 1] and state["burning"], state
    while (state := await arena.get_furnace(pos=furnace))["output"] is None:
        assert loop.time() < deadline, f"no baked potato after 60 s: {state}"
        await asyncio.sleep(0.25)
    state, second_start = await started_at()
    assert state["output"] == ["baked_potato", 1] and state["input"] == ["potato", 1], state
    # the second potato started the tick the first came out
    assert abs((second_start - first_start) - 200) <= 3, f"first baked potato after {second_start - first_start} ticks"
    taken = await alice.eval(
        FIND % ("furnace", "furnace")
        + """
        const f = await bot.openFurnace(block)
        await sleep(200)
        const out = await f.takeOutput()
        f.close()
        await sleep(200)
        return out && [out.name, out.count]
    """
    )
    assert taken == ["baked_potato", 1]
    assert await count(arena, "alice", "baked_potato") == 1


async def test_furnace_without_fuel_does_nothing(arena, bots, area):
    furnace = area.at(3, 4, 2)
    await arena.set_block(pos=furnace, block="furnace")
    await arena.set_furnace(pos=furnace, input=["beef", 3])
    await wait_ticks(arena, 20)
    state = await arena.get_furnace(pos=furnace)
    assert state == {"input": ["beef", 3], "fuel": None, "output": None, "burning": False, "progress": 0}
