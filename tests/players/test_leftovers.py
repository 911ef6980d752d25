"""No action outlives its run (js/bot/gate.js): an action mineflayer still carries out after its run
stopped (the head turning before a dig, a use on a block or a placement; a dig it still holds) acts
neither for the stopped run nor for the next one. Each test stops the run at the moment the bot itself
reports that the action began (the agent code saves 'began' right after calling it), never after a
fixed sleep, and starts the next run at once, while mineflayer is still turning the head."""

from __future__ import annotations

import asyncio

FACE_AWAY = "await bot.lookAt(new Vec3({x}, 5.6, -20), true)\nawait bot.waitForTicks(5)"


async def stop_when_begun(p, code: str) -> None:
    """Run `code` (which saves 'began' once its action is under way) and stop it at that moment."""
    began = asyncio.Event()
    run = asyncio.create_task(p.run(code, on_event=lambda e: e[0] == "onSave" and began.set()))
    await asyncio.wait_for(began.wait(), 10)
    await p.stop()
    await asyncio.wait_for(run, 3)


async def face_away(area, p) -> None:
    # facing -z, the block to act on at +z: half a turn (about a second at mineflayer's 3 rad/s)
    await p.run(FACE_AWAY.format(x=area.x0 + 0.5))


async def holding_slime(area, make_player):
    p = await make_player(area, 0, 0, {"slime_block": 4})
    await p.run("await bot.equip(mcData.itemsByName.slime_block.id, 'hand')")
    await face_away(area, p)
    return p


USE = "const p = bot.activateBlock(bot.blockAt(new Vec3({x}, 3, 2)))\nbot.save('began')\nawait p"
PLACE = "const p = bot.placeBlock(bot.blockAt(new Vec3({x}, 3, 2)), new Vec3(0, 1, 0))\nbot.save('began')\nawait p"


async def test_a_use_on_a_block_still_turning_at_stop_acts_neither_for_its_run_nor_the_next(server, area, make_player):
    for code in (USE, PLACE):  # holding slime: using the ground at (0, 3, 2) places a block at (0, 4, 2)
        await area.blocks((0, 4, 2, "air"))
        p = await holding_slime(area, make_player)
        await stop_when_begun(p, code.format(x=area.x0))
        await p.run("await bot.waitForTicks(40)")  # the next run (the next episode) while the head turns
        assert (await server.get_block(pos=area.at(0, 4, 2)))["name"] == "air", code
        await stop_when_begun(p, FACE_AWAY.format(x=area.x0 + 0.5) + "\n" + code.format(x=area.x0))
        await asyncio.sleep(1.5)  # no next run: the turn ends with no run at all
        assert (await server.get_block(pos=area.at(0, 4, 2)))["name"] == "air", code


DIG = "const p = bot.dig(bot.blockAt(new Vec3({x}, 4, 2)))\nbot.save('began')\nawait p"


async def test_a_dig_still_turning_at_stop_breaks_nothing_in_its_run_or_the_next(server, area, make_player):
    await area.blocks((0, 4, 2, "slime_block"))
    p = await make_player(area, 0, 0)
    await face_away(area, p)
    await stop_when_begun(p, DIG.format(x=area.x0))
    await p.run("await bot.waitForTicks(40)")
    assert (await server.get_block(pos=area.at(0, 4, 2)))["name"] == "slime_block"
    await stop_when_begun(p, FACE_AWAY.format(x=area.x0 + 0.5) + "\n" + DIG.format(x=area.x0))
    await asyncio.sleep(1.5)
    assert (await server.get_block(pos=area.at(0, 4, 2)))["name"] == "slime_block"


async def test_a_new_run_starts_with_no_dig_held_over_from_the_stopped_one(server, area, make_player):
    # a long dig (stone by hand, 7.5 s) whose start was dropped at the stop: mineflayer still holds it,
    # and the next run's first dig would send its cancel; the next run starts without it
    await area.blocks((0, 4, 2, "stone"), (20, 4, 2, "slime_block"))
    p = await make_player(area, 0, 0)
    await face_away(area, p)
    await stop_when_begun(p, DIG.format(x=area.x0))
    await asyncio.sleep(1.2)  # the turn ends: mineflayer now holds the dig (its start dropped)
    await p.reset(position=area.at(20, 4, 0))  # the next episode's spawn
    events = await p.run(
        f"bot.save(bot.targetDigBlock ? 'held' : 'none')\nawait bot.dig(bot.blockAt(new Vec3({area.x0 + 20}, 4, 2)))"
    )
    assert [e[1]["onSave"] for e in events if e[0] == "onSave"] == ["none"]
    assert (await server.get_block(pos=area.at(20, 4, 2)))["name"] == "air"
    assert (await server.get_block(pos=area.at(0, 4, 2)))["name"] == "stone"
