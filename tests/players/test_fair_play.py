"""The rows of issue 12's table, forged from sandboxed agent code: the server refuses what a
vanilla server refuses, its state stays unchanged, and the refusal reaches the player's own events
(an onChat line "[refused] ...") as well as the control channel."""

from __future__ import annotations

import asyncio

from pillagerbench.players.events import chat_log, errors
from tests.players.conftest import count


async def _refused(server, q) -> list[dict]:
    await asyncio.sleep(0.3)
    return [e for e in (q.get_nowait() for _ in range(q.qsize())) if e.get("event") == "refused"]


async def _pos(server, name):
    return next(p["pos"] for p in await server.request("players") if p["name"] == name)


async def test_teleporting_by_setting_the_position_is_put_back_and_cannot_dig_there(server, area, make_player):
    p = await make_player(area, 0, 0)
    await area.blocks((-9, 4, 6, "red_mushroom_block"))
    start = await _pos(server, p.name)
    q = server.control.subscribe()
    try:
        events = await p.run(
            f"bot.entity.position.set({area.x0 - 9.5}, 4, 6.5)\nawait bot.waitForTicks(20)\n"
            f"await bot.dig(bot.blockAt(new Vec3({area.x0 - 9}, 4, 6)), true).catch(() => {{}})\n"
            "await bot.waitForTicks(5)"
        )
        got = await _refused(server, q)
    finally:
        server.control.unsubscribe(q)
    assert await _pos(server, p.name) == start
    assert (await server.request("get_block", pos=area.at(-9, 4, 6)))["name"] == "red_mushroom_block"
    assert got[0]["action"] == "move" and "moved too quickly" in got[0]["reason"], got
    assert any(line.startswith("[refused] move: moved too quickly") for line in chat_log(events))


async def test_rising_into_the_air_is_put_back(server, area, make_player):
    p = await make_player(area, 0, 0)
    q = server.control.subscribe()
    try:
        events = await p.run(
            "bot.entity.position.set(bot.entity.position.x, 20, bot.entity.position.z)\nawait bot.waitForTicks(40)"
        )
        got = await _refused(server, q)
    finally:
        server.control.unsubscribe(q)
    assert (await _pos(server, p.name))[1] < 5.5
    assert got and got[0]["action"] == "move" and "moved up too quickly" in got[0]["reason"]
    assert any("[refused] move" in line for line in chat_log(events))


async def test_digging_a_block_out_of_reach_is_refused(server, area, make_player):
    p = await make_player(area, 0, 0)
    await area.blocks((15, 4, 6, "red_mushroom_block"))  # 16.7 blocks away
    q = server.control.subscribe()
    try:
        events = await p.run(
            f"await bot.dig(bot.blockAt(new Vec3({area.x0 + 15}, 4, 6)), true)\nawait bot.waitForTicks(5)"
        )
        got = await _refused(server, q)
    finally:
        server.control.unsubscribe(q)
    assert (await server.request("get_block", pos=area.at(15, 4, 6)))["name"] == "red_mushroom_block"
    assert [g["action"] for g in got] == ["dig"] and "too far to dig red_mushroom_block" in got[0]["reason"]
    assert any(line.startswith("[refused] dig: too far") for line in chat_log(events))


async def test_a_chest_out_of_reach_cannot_be_opened(server, area, make_player):
    p = await make_player(area, 0, 0)
    await area.blocks((10, 4, 3, "chest"))  # 10.7 blocks away
    chest = area.at(10, 4, 3)
    await server.request("set_chest", pos=chest, items={"gold_nugget": 64})
    q = server.control.subscribe()
    try:
        events = await p.run(
            f"const v = new Vec3({chest[0]}, 4, 3)\n"
            "for (let i = 0; i < 40 && bot.blockAt(v).name !== 'chest'; i++) await bot.waitForTicks(1)\n"
            "const c = await bot.openContainer(bot.blockAt(v))\n"
            "await c.withdraw(mcData.itemsByName.gold_nugget.id, null, 64)",
            timeout=30,
        )
        got = await _refused(server, q)
    finally:
        server.control.unsubscribe(q)
    assert await server.request("get_chest", pos=chest) == {"gold_nugget": 64}
    assert await count(server, p.name, "gold_nugget") == 0
    assert [g["action"] for g in got] == ["use_block"] and "too far to use chest" in got[0]["reason"], (
        got,
        errors(events),
    )
    assert any(line.startswith("[refused] use_block") for line in chat_log(events))


async def test_honest_primitives_trip_nothing(server, area, make_player):
    p = await make_player(area, 0, 0, {"dirt": 2}, primitives=["mineBlock", "placeItem", "useChest"])
    await area.blocks((8, 4, 4, "red_mushroom_block"), (9, 4, -4, "chest"))
    await server.request("set_chest", pos=area.at(9, 4, -4), items={"gold_nugget": 5})
    q = server.control.subscribe()
    try:
        await p.run(
            f"await mineBlock(bot, 'red_mushroom_block', 1)\nawait placeItem(bot, 'dirt', new Vec3({area.x0 + 3}, 4, 0))\n"
            f"await getItemFromChest(bot, new Vec3({area.x0 + 9}, 4, -4), {{gold_nugget: 5}})",
            timeout=60,
        )
        got = await _refused(server, q)
    finally:
        server.control.unsubscribe(q)
    assert (await server.request("get_block", pos=area.at(8, 4, 4)))["name"] == "air"
    assert (await server.request("get_block", pos=area.at(3, 4, 0)))["name"] == "dirt"
    assert await count(server, p.name, "gold_nugget") == 5
    assert got == []
