"""Upstream's bot plugins in the sandbox (mineflayer-collectblock, mineflayer-tool, mineflayer-pvp)
on the real server: they act through the same server rules, behind the same run checks, and a
stopped run stops them."""

from __future__ import annotations

import asyncio

from pillagerbench.players.events import chats_by, errors
from tests.players.conftest import count

SEE = "for (let i = 0; i < 40 && !bot.nearestEntity(e => e.name === '%s'); i++) await bot.waitForTicks(1)\n"


async def test_tool_and_collectblock(server, area, make_player):
    await area.blocks((3, 4, 0, "oak_planks"), (3, 4, 2, "oak_planks"))
    p = await make_player(area, 0, 0, {"wooden_axe": 1, "dirt": 1})
    events = await p.run(
        """
const planks = bot.findBlocks({ matching: mcData.blocksByName.oak_planks.id, maxDistance: 8, count: 2 })
await bot.tool.equipForBlock(bot.blockAt(planks[0]), {})
bot.chat('held ' + bot.heldItem.name)
await bot.collectBlock.collect(planks.map(p => bot.blockAt(p)))
bot.chat('left ' + bot.findBlocks({ matching: mcData.blocksByName.oak_planks.id, maxDistance: 8, count: 2 }).length)
"""
    )
    assert errors(events) == [], errors(events)
    assert chats_by(events, p.name) == ["held wooden_axe", "left 0"]
    assert await count(server, p.name, "oak_planks") == 2  # dug and picked up, as the server saw it
    for dz in (0, 2):
        assert (await server.get_block(pos=area.at(3, 4, dz)))["name"] == "air"


async def test_pvp_attacks_until_the_mob_dies(server, area, make_player):
    p = await make_player(area, 0, 0, {"wooden_sword": 1})
    mob = await server.summon(mob="chicken", pos=area.at(5.5, 4, 0.5))
    events = await p.run(
        SEE % "chicken"
        + """
await bot.equip(bot.inventory.items()[0], 'hand')
const chicken = bot.nearestEntity(e => e.name === 'chicken')
await bot.pvp.attack(chicken)
for (let i = 0; i < 200 && bot.pvp.target; i++) await bot.waitForTicks(1)
bot.chat('target ' + (bot.pvp.target ? 'still there' : 'gone'))
"""
    )
    assert errors(events) == [], errors(events)
    assert chats_by(events, p.name) == ["target gone"]
    assert mob not in [m["id"] for m in await server.mobs()]


async def test_a_stopped_run_stops_pvp(server, area, make_player):
    p = await make_player(area, 0, 0)
    mob = await server.summon(mob="cow", pos=area.at(5.5, 4, 0.5))  # 10 HP: bare hands need a while
    events = await p.run(
        SEE % "cow"
        + """
await bot.pvp.attack(bot.nearestEntity(e => e.name === 'cow'))
await bot.waitForTicks(400)
""",
        timeout=1,
    )
    assert any("Timeout" in e for e in errors(events)), errors(events)
    await asyncio.sleep(1.5)
    after = await p.run("bot.chat('target ' + (bot.pvp.target ? 'kept' : 'none'))")
    assert chats_by(after, p.name) == ["target none"]
    assert mob in [m["id"] for m in await server.mobs()]  # nobody went on hitting it
