"""Crafting with real mineflayer `bot.craft`, checked against the server's inventory."""

from __future__ import annotations

import pytest

from tests.server.conftest import count

CRAFT = """
let table = null
for (let i = 0; i < 40 && !table; i++, await sleep(50)) table = bot.findBlock({ matching: mcData.blocksByName.crafting_table.id, maxDistance: 6 })
const item = mcData.itemsByName['%s'].id
const recipe = bot.recipesFor(item, null, 1, table)[0]
if (!recipe) throw new Error('no recipe for %s with ' + JSON.stringify(bot.inventory.items().map(i => [i.name, i.count])))
await bot.craft(recipe, %d, table)
await sleep(300)
return bot.inventory.items().map(i => [i.name, i.count])
"""

# (result, ingredients given, times, expected server inventory afterwards)
TABLE_RECIPES = [
    ("bread", {"wheat": 6}, 2, {"bread": 2}),
    ("cake", {"milk_bucket": 3, "sugar": 2, "egg": 1, "wheat": 3}, 1, {"cake": 1, "bucket": 3}),
    ("cookie", {"wheat": 2, "cocoa_beans": 1}, 1, {"cookie": 8}),
    ("pumpkin_pie", {"pumpkin": 1, "sugar": 1, "egg": 1}, 1, {"pumpkin_pie": 1}),
    ("beetroot_soup", {"beetroot": 6, "bowl": 1}, 1, {"beetroot_soup": 1}),
    ("mushroom_stew", {"red_mushroom": 1, "brown_mushroom": 1, "bowl": 1}, 1, {"mushroom_stew": 1}),
    ("golden_carrot", {"carrot": 1, "gold_nugget": 8}, 1, {"golden_carrot": 1}),
    ("bowl", {"oak_planks": 3}, 1, {"bowl": 4}),
    ("sugar", {"sugar_cane": 2}, 2, {"sugar": 2}),
]


@pytest.mark.parametrize("result,ingredients,times,expected", TABLE_RECIPES, ids=[r[0] for r in TABLE_RECIPES])
async def test_crafting_table_recipes(arena, bots, area, result, ingredients, times, expected):
    alice, _ = bots
    await arena.set_block(pos=area.at(3, 4, 2), block="crafting_table")
    await area.put(alice, 2, 2, ingredients)
    believed = await alice.eval(CRAFT % (result, result, times))
    server = {s["name"]: 0 for s in await arena.inventory(player="alice")}
    for s in await arena.inventory(player="alice"):
        server[s["name"]] += s["count"]
    assert server == expected
    assert dict(believed) == expected  # the client agrees with the server


async def test_inventory_2x2_crafting_planks_and_sticks(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 2, 2, {"oak_log": 1})
    await alice.eval("""
        await bot.craft(bot.recipesFor(mcData.itemsByName.oak_planks.id, null, 1, null)[0], 1, null)
        await bot.craft(bot.recipesFor(mcData.itemsByName.stick.id, null, 1, null)[0], 1, null)
    """)
    assert await count(arena, "alice", "oak_log") == 0
    assert await count(arena, "alice", "oak_planks") == 2
    assert await count(arena, "alice", "stick") == 4


async def test_crafting_without_ingredients_gives_nothing(arena, bots, area):
    alice, _ = bots
    await arena.set_block(pos=area.at(3, 4, 2), block="crafting_table")
    await area.put(alice, 2, 2, {"wheat": 2})
    # Fake the client's belief that it holds 3 wheat, then click the result slot.
    await alice.eval("""
        let table = null
        for (let i = 0; i < 40 && !table; i++, await sleep(50)) table = bot.findBlock({ matching: mcData.blocksByName.crafting_table.id, maxDistance: 6 })
        if (!table) throw new Error('no crafting table in sight: ' + JSON.stringify([bot.entity.position, bot.blockAt(bot.entity.position.offset(0.5, 0, -0.5).floored()), bot.blockAt(bot.entity.position.offset(0, -1, 0))]))
        const opened = new Promise((resolve, reject) => { bot.once('windowOpen', resolve); setTimeout(() => reject(new Error('crafting table did not open')), 5000) })
        await bot.activateBlock(table)
        const win = await opened
        const s = win.findInventoryItem(mcData.itemsByName.wheat.id).slot
        await bot.clickWindow(s, 0, 0)
        for (const dest of [1, 2]) await bot.clickWindow(dest, 1, 0)
        bot._client.write('window_click', { windowId: win.id, slot: 3, mouseButton: 0, action: 90, mode: 0,
          item: { present: true, itemId: mcData.itemsByName.wheat.id, itemCount: 1 } })
        bot._client.write('window_click', { windowId: win.id, slot: 0, mouseButton: 0, action: 91, mode: 0,
          item: { present: true, itemId: mcData.itemsByName.bread.id, itemCount: 1 } })
        await sleep(300)
        bot.closeWindow(win)
        await sleep(300)
    """)
    assert await count(arena, "alice", "bread") == 0
    assert await count(arena, "alice", "wheat") == 2  # the grid went back to the inventory on close
