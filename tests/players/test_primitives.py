"""Every control primitive against the real server, in the situations the scenarios use.

Assertions read the server's own state (inventory, blocks, chests) through the control channel.
The module's tests share two players (`make_player` here): each test gets them reset into its own
area with its own inventory, as a match resets its players before each episode.
"""

from __future__ import annotations

import asyncio

import pytest_asyncio

from pillagerbench.players import Player
from pillagerbench.players.events import chats_by, errors, last_observation, saves
from tests.players.conftest import Area, close_players, count, start_player


@pytest_asyncio.fixture(scope="module", loop_scope="session")
async def pool(server, tmp_path_factory):
    """The module's two players, logged in once (a login cost a test 1-1.5 s)."""
    area, made = Area(server), []
    log_dir = tmp_path_factory.mktemp("primitives")
    for dx in (0, 4):
        await start_player(server, area, log_dir, made, dx, 0)
    yield made
    await close_players(server, made)


@pytest_asyncio.fixture(loop_scope="session")
async def make_player(server, pool):
    """As conftest's, on the module's players: make_player(area, dx, dz, inventory) -> the next one,
    reset (its code stopped, its inventory set) to stand at (dx, dz) of the test's area. Fails the test
    if its code restarted a player; the mobs it left are removed."""
    given: list[Player] = []
    restarts = [p.bot.restarts for p in pool]

    async def make(area: Area, dx: float = 0, dz: float = 0, inventory: dict | None = None) -> Player:
        p = pool[len(given)]
        given.append(p)
        await p.reset(position=area.at(dx, 4, dz), inventory=inventory or {})
        return p

    yield make
    await server.remove_entities()
    assert [p.bot.restarts for p in pool] == restarts and all(p.bot.alive for p in pool)


async def test_mine_slime_and_mushroom_blocks(server, area, make_player):
    await server.seed(seed=7)
    # a slime plus and a red mushroom (2-high stem, 5 cap blocks) as in Mushroom War
    await area.blocks(*[(4 + dx, 4, dz, "slime_block") for dx, dz in [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)]])
    stem = [(8, 4, 4, "mushroom_stem"), (8, 5, 4, "mushroom_stem")]
    cap = [(8 + dx, 5, 4 + dz, "red_mushroom_block") for dx, dz in [(1, 0), (-1, 0), (0, 1), (0, -1)]] + [
        (8, 6, 4, "red_mushroom_block")
    ]
    await area.blocks(*stem, *cap)
    p = await make_player(area, 0, 0)
    events = await p.run("await mineBlock(bot, 'slime_block', 5)\nawait mineBlock(bot, 'red_mushroom_block', 5)")
    assert errors(events) == []
    said = chats_by(events, p.name)
    assert "Mined 5 slime_block" in said and "Mined 5 red_mushroom_block" in said
    assert saves(events) == ["slime_block_mined", "red_mushroom_block_mined"]
    assert await count(server, p.name, "slime_block") == 5
    for b in cap:
        assert (await server.get_block(pos=area.at(*b[:3])))["name"] == "air"
    assert (await server.get_block(pos=area.at(8, 4, 4)))["name"] == "mushroom_stem"
    obs = last_observation(events)
    assert obs["inventory"].get("slime_block") == 5
    assert obs["inventory"].get("red_mushroom", 0) == await count(server, p.name, "red_mushroom")


async def test_mine_block_missing_counts_failures(server, area, make_player):
    p = await make_player(area)
    events = await p.run("for (let i = 0; i < 12; i++) await mineBlock(bot, 'diamond_ore', 1)")
    assert chats_by(events, p.name).count("No diamond_ore nearby, please explore first") == 11
    assert any("mineBlock failed too many times" in e and "at line 1" in e for e in errors(events))
    events = await p.run("await mineBlock(bot, 'no_such_block')\n")
    assert errors(events) and "No block named no_such_block" in errors(events)[0]


async def test_place_item(server, area, make_player):
    p = await make_player(area, 0, 0, {"slime_block": 2})
    target = area.at(2, 4, 1)
    events = await p.run(
        f"await placeItem(bot, 'slime_block', new Vec3({target[0]}, 4, 1))\n"
        "await placeItem(bot, 'slime_block', new Vec3(%d, 9, 1))" % target[0]
    )
    assert (await server.get_block(pos=target))["name"] == "slime_block"
    said = chats_by(events, p.name)
    assert "Placed slime_block" in said
    assert "No block to place slime_block on. You cannot place a floating block." in said
    assert await count(server, p.name, "slime_block") == 1
    assert saves(events) == ["slime_block_placed"]


async def test_craft_bread_and_cake(server, area, make_player):
    await area.blocks((2, 4, 2, "crafting_table"))
    p = await make_player(area, 0, 0, {"wheat": 9, "milk_bucket": 3, "sugar": 2, "egg": 1})
    events = await p.run(
        "await craftItem(bot, 'bread', 2)\nawait craftItem(bot, 'cake', 1)\nawait craftItem(bot, 'bread', 5)"
    )
    said = chats_by(events, p.name)
    assert "I can make bread" in said and "I did the recipe for bread 2 times" in said
    assert "I did the recipe for cake 1 times" in said
    assert "I cannot make bread because I need: 3 more wheat" in said
    assert await count(server, p.name, "bread") == 2
    assert await count(server, p.name, "cake") == 1
    assert await count(server, p.name, "bucket") == 3
    assert await count(server, p.name, "wheat") == 0


async def test_smelt_potato(server, area, make_player):
    await area.blocks((2, 4, 0, "furnace"))
    p = await make_player(area, 0, 0, {"potato": 1, "coal": 1})
    events = await p.run("await smeltItem(bot, 'potato', 'coal', 1)")
    assert errors(events) == []
    assert "Smelted 1 potato." in chats_by(events, p.name)
    # upstream's waits a fixed 240 ticks per item before taking the output (the furnace needs 200)
    tick = {d["onChat"]: d["status"]["elapsedTime"] for kind, d in events if kind == "onChat"}
    started, smelted = tick[f"<{p.name}> Smelting 1 potato with coal"], tick[f"<{p.name}> Smelted 1 potato."]
    assert smelted - started >= 235, (started, smelted)
    assert await count(server, p.name, "baked_potato") == 1
    assert await count(server, p.name, "potato") == 0


async def test_chest_take_eggs_deposit_and_check(server, area, make_player):
    chest = area.at(3, 4, 0)
    await area.blocks((3, 4, 0, "chest"))
    await server.set_chest(pos=chest, items={"egg": 5, "bucket": 2})
    p = await make_player(area, 0, 0, {"bowl": 3})
    v = f"new Vec3({chest[0]}, 4, 0)"
    events = await p.run(
        f"await getItemFromChest(bot, {v}, {{egg: 2, sugar: 1}})\n"
        f"await depositItemIntoChest(bot, {v}, {{bowl: 3}})\n"
        f"const c = await checkItemInsideChest(bot, {v})\n"
        "if (c.bowl !== 3) throw new Error('bad contents ' + JSON.stringify(c))"
    )
    assert errors(events) == []
    assert "I don't see sugar in this chest" in chats_by(events, p.name)
    assert await count(server, p.name, "egg") == 2
    assert await server.get_chest(pos=chest) == {"egg": 3, "bucket": 2, "bowl": 3}
    chests = last_observation(events)["nearbyChests"]
    assert chests[f"({chest[0]}, 4, 0)"] == {"egg": 3, "bucket": 2, "bowl": 3}
    events = await p.run(f"await getItemFromChest(bot, new Vec3({chest[0]}, 4, 5), {{egg: 1}})")
    assert "No chest at" in errors(events)[0]
    assert last_observation(events)["nearbyChests"][f"({chest[0]}, 4, 5)"] == "Invalid"


async def test_harvest_and_replant_wheat(server, area, make_player):
    plots = [(4 + i, 3, 0) for i in range(3)]
    await area.blocks(*[(x, y, z, "farmland") for x, y, z in plots])
    await area.blocks(*[(x, 4, z, "wheat", {"age": 7}) for x, y, z in plots])
    await area.blocks((8, 3, 0, "farmland"), (8, 4, 0, "wheat", {"age": 3}))  # not ripe: stays
    p = await make_player(area, 0, 0, {"wheat_seeds": 5})
    events = await p.run(f"await harvestWheat(bot, new Vec3({area.x0 + 5}, 4, 0))\nawait plantWheatSeeds(bot)")
    assert errors(events) == []
    said = chats_by(events, p.name)
    assert "Harvesting wheat" in said and "Harvested 3 wheat" in said
    assert "All available land has been planted with wheat_seeds." in said
    assert await count(server, p.name, "wheat") == 3
    for x, _, z in plots:
        b = await server.get_block(pos=area.at(x, 4, z))
        assert b["name"] == "wheat" and int(b["properties"]["age"]) == 0, b
    young = await server.get_block(pos=area.at(8, 4, 0))
    assert int(young["properties"]["age"]) == 3


async def test_till_and_plant_potatoes(server, area, make_player):
    await area.blocks((4, 3, 0, "dirt"), (5, 3, 0, "dirt"))
    p = await make_player(area, 0, 0, {"wooden_hoe": 1, "potato": 1})
    events = await p.run("await tillLand(bot, ['dirt'])\nawait plantPotatoes(bot)")
    assert errors(events) == []
    assert "All available land has been tilled." in chats_by(events, p.name)
    names = {(await server.get_block(pos=area.at(x, 3, 0)))["name"] for x in (4, 5)}
    assert names == {"farmland"}
    assert await count(server, p.name, "potato") == 0
    planted = [(await server.get_block(pos=area.at(x, 4, 0)))["name"] for x in (4, 5)]
    assert planted.count("potatoes") == 1


# the mob was summoned a moment ago: let its spawn packet reach the bot before the primitive looks
SEE = "for (let i = 0; i < 40 && !bot.nearestEntity(e => e.name === '%s'); i++) await bot.waitForTicks(1)\n"


async def test_milk_cow(server, area, make_player):
    p = await make_player(area, 0, 0, {"bucket": 3})  # log in first: see the note in conftest
    await server.summon(mob="cow", pos=area.at(5.5, 4, 0.5))
    # cake_beetroot milks in a loop: each call milks (every other one failed while the server took
    # clicks less than 200 ms apart for one)
    events = await p.run(SEE % "cow" + "for (let i = 0; i < 3; i++) await milkCow(bot)")
    assert errors(events) == []
    assert chats_by(events, p.name).count("Milked cow") == 3, chats_by(events, p.name)
    assert await count(server, p.name, "milk_bucket") == 3
    assert await count(server, p.name, "bucket") == 0
    assert "cow" in last_observation(events)["status"]["entities"]


async def test_kill_mob(server, area, make_player):
    await server.seed(seed=3)
    p = await make_player(area, 0, 0, {"wooden_sword": 1})
    mob = await server.summon(mob="chicken", pos=area.at(5.5, 4, 0.5))
    events = await p.run(
        SEE % "chicken" + "await bot.equip(bot.inventory.items()[0], 'hand')\nawait killMob(bot, 'chicken', 20)"
    )
    assert errors(events) == []
    assert "Killed chicken!" in chats_by(events, p.name)
    assert saves(events) == ["chicken_killed"]
    assert mob not in [m["id"] for m in await server.mobs()]
    assert await count(server, p.name, "chicken") == 1


async def test_give_food_to_another_player(server, area, make_player):
    giver = await make_player(area, 0, 0, {"bread": 3})
    taker = await make_player(area, 4, 3, {})
    events = await giver.run(f"return await giveToPlayer(bot, 'bread', '{taker.name}', 2)")
    assert errors(events) == []
    assert f"Gave 2 bread to {taker.name}" in chats_by(events, giver.name)
    for _ in range(50):
        if await count(server, taker.name, "bread") == 2:
            break
        await asyncio.sleep(0.1)
    assert await count(server, taker.name, "bread") == 2
    assert await count(server, giver.name, "bread") == 1
    events = await giver.run("await giveToPlayer(bot, 'cake', 'Nobody', 1)")
    assert "Could not find Nobody." in errors(events)[0]


async def test_signals_between_two_players(server, area, make_player):
    a = await make_player(area, 0, 0)
    b = await make_player(area, 2, 0)
    waiting = asyncio.create_task(
        a.run("const got = await waitSignal(bot, null, 10000)\nif (!got) throw new Error('no signal')")
    )
    await asyncio.sleep(0.5)
    sent = await b.run(f"await sendSignal(bot, '{a.name}')")
    events = await asyncio.wait_for(waiting, 12)
    assert errors(events) == []
    said = chats_by(events, a.name)
    assert said[0] == "[waiting signal]" and "[signal recieved]" in said
    assert f"[{a.name} signal]" in chats_by(sent, b.name)
    events = await a.run("return await waitSignal(bot, null, 300)")
    assert "[signal timeout]" in chats_by(events, a.name)


async def test_explore_until(server, area, make_player):
    p = await make_player(area, 0, 0)
    x_goal = area.x0 + 4
    events = await p.run(
        f"const r = await exploreUntil(bot, new Vec3(1, 0, 0), 20, () => bot.entity.position.x > {x_goal})\n"
        "if (!r) throw new Error('did not get there')"
    )
    assert errors(events) == []
    assert "Explore success." in chats_by(events, p.name)
    events = await p.run("await exploreUntil(bot, new Vec3(0, 0, 1), 0.5, () => false)")
    assert "Max exploration time reached" in chats_by(events, p.name)


async def test_harvest_berries_and_destroy_crop(server, area, make_player):
    await server.seed(seed=11)
    await area.blocks(
        (4, 4, 0, "sweet_berry_bush", {"age": 3}),
        (5, 4, 0, "sweet_berry_bush", {"age": 1}),
        (4, 3, 3, "farmland"),
        (4, 4, 3, "carrots", {"age": 2}),
        (5, 3, 3, "farmland"),
        (5, 4, 3, "carrots", {"age": 5}),
    )
    p = await make_player(area, 0, 0)
    events = await p.run(f"await harvestBerries(bot, new Vec3({area.x0 + 4}, 4, 0))\nawait destroyCrop(bot, 'carrots')")
    assert errors(events) == []
    said = chats_by(events, p.name)
    assert "Harvested 1 sweet_berry_bush" in said and "Destroying all carrots nearby" in said
    assert await count(server, p.name, "sweet_berries") >= 2
    bush = await server.get_block(pos=area.at(4, 4, 0))
    assert bush["name"] == "sweet_berry_bush" and int(bush["properties"]["age"]) == 1  # picked, the bush stays
    for x in (4, 5):
        assert (await server.get_block(pos=area.at(x, 4, 3)))["name"] == "air"


async def planted(area, make_player, blocks, item, count_, call):
    """Put `blocks`, give a player `count_` of `item`, run `call`; the player, once it said it planted."""
    await area.blocks(*blocks)
    p = await make_player(area, 0, 0, {item: count_})
    events = await p.run(f"await {call}(bot)")
    assert errors(events) == []
    assert f"All available land has been planted with {item}." in chats_by(events, p.name)
    return p


async def test_berries_are_planted_on_farmland_and_dirt_never_on_grass(server, area, make_player):
    # upstream's plantSweetBerryBushes searches farmland and dirt: the lawn around stays a lawn
    blocks = [(3, 3, 0, "dirt"), (5, 3, 0, "farmland")]
    p = await planted(area, make_player, blocks, "sweet_berries", 10, "plantSweetBerryBushes")
    assert await count(server, p.name, "sweet_berries") == 8
    for x in (3, 5):
        assert (await server.get_block(pos=area.at(x, 4, 0)))["name"] == "sweet_berry_bush"
    bushes = await server.find_blocks(names=["sweet_berry_bush"], center=area.at(0, 4, 0), radius=32)
    assert len(bushes) == 2


async def test_planting_walks_on_to_every_free_block_after_the_seeds_run_out(server, area, make_player):
    # upstream's plantCrop visits every candidate block, clicking with an empty hand once the seeds
    # are gone; it does not stop at the last seed
    blocks = [(x, 3, 0, "farmland") for x in (3, 9, 14)]
    p = await planted(area, make_player, blocks, "sweet_berries", 1, "plantSweetBerryBushes")
    names = [(await server.get_block(pos=area.at(x, 4, 0)))["name"] for x in (3, 9, 14)]
    assert names == ["sweet_berry_bush", "air", "air"]
    x = last_observation(await p.observe())["status"]["position"]["x"] - area.x0
    assert x > 10, x  # went on to the farthest block


async def test_cocoa_planting_clicks_the_logs_top_as_upstreams_and_keeps_the_beans(server, area, make_player):
    # upstream's plantCrop right-clicks every candidate on its top face (activateBlock's default);
    # vanilla puts no cocoa pod on top of a log, so upstream's plantCocoaBeans planted nothing
    p = await planted(area, make_player, [(4, y, 0, "jungle_log") for y in (4, 5)], "cocoa_beans", 3, "plantCocoaBeans")
    pods = await server.find_blocks(names=["cocoa"], center=area.at(4, 4, 0), radius=8)
    assert pods == [] and await count(server, p.name, "cocoa_beans") == 3


async def test_sugar_cane_is_planted_on_sand_beside_water_not_on_grass(server, area, make_player):
    await area.blocks((3, 3, 0, "sand"), (3, 3, -1, "water"), (6, 3, 0, "sand"))
    p = await make_player(area, 0, 2, {"sugar_cane": 10})
    events = await p.run("await plantSugarCane(bot)")
    assert errors(events) == []
    assert (await server.get_block(pos=area.at(3, 4, 0)))["name"] == "sugar_cane"
    assert (await server.get_block(pos=area.at(6, 4, 0)))["name"] == "air"  # no water beside it
    canes = await server.find_blocks(names=["sugar_cane"], center=area.at(0, 4, 0), radius=32)
    assert len(canes) == 1


async def test_craft_item_without_a_table_throws_as_upstream(server, area, make_player):
    p = await make_player(area, 0, 0, {"wheat": 3, "milk_bucket": 3, "sugar": 2, "egg": 1, "sugar_cane": 1})
    events = await p.run("await craftItem(bot, 'sugar', 1)\nawait craftItem(bot, 'cake', 1)")
    said = chats_by(events, p.name)
    assert "Craft without a crafting table" in said and "I did the recipe for sugar 1 times" in said
    assert errors(events) and "No crafting table nearby" in errors(events)[0]
    assert await count(server, p.name, "cake") == 0


async def test_no_fail_counter_where_upstream_had_none(server, area, make_player):
    # upstream's placeItem (item missing), smeltItem (no item, no furnace), tillLand and milkCow count no
    # failures: twelve in a row go on without an error
    p = await make_player(area, 0, 0)
    events = await p.run(
        "for (let i = 0; i < 12; i++) {\n"
        "  await placeItem(bot, 'slime_block', bot.entity.position.offset(2, 0, 0))\n"
        "  await smeltItem(bot, 'potato', 'coal', 1)\n"
        "  await tillLand(bot)\n"
        "  await milkCow(bot)\n"
        "  await bot.waitForTicks(25)\n"  # 4 chats a loop: under the 25 chats per 100 ticks limit
        "}\nreturn 'done'"
    )
    assert errors(events) == []
    said = chats_by(events, p.name)
    assert said.count("No slime_block in inventory") == 12
    assert said.count("No hoe in inventory.") == 12
    assert said.count("No cow nearby, please explore first") == 12


async def dug_while(server, area, player, code: str) -> tuple[list, list[int]]:
    """Run `code` on `player`; its events and the x (relative to the area) of each block dug, in order."""
    q = server.control.subscribe()
    try:
        events = await player.run(code)
        await asyncio.sleep(0.3)
        dug = [e["pos"][0] - area.x0 for e in (q.get_nowait() for _ in range(q.qsize())) if e["event"] == "block_dug"]
    finally:
        server.control.unsubscribe(q)
    return events, dug


async def test_mine_block_goes_to_the_target_nearest_to_the_bot_each_time(server, area, make_player):
    # searched around a point near the far end, the three blocks are found far-first; upstream's
    # collectblock (and ours) digs the one nearest to the bot each time: near, middle, far
    xs = (2, 6, 10)
    await area.blocks(*[(x, 4, 0, "slime_block") for x in xs])
    p = await make_player(area, 0, 0)
    events, dug = await dug_while(
        server, area, p, f"await mineBlock(bot, 'slime_block', 3, new Vec3({area.x0 + 9}, 4, 0), 12)"
    )
    assert errors(events) == []
    assert dug == list(xs)


async def test_harvest_goes_to_the_crop_nearest_to_the_bot_each_time(server, area, make_player):
    xs = (2, 6, 10)
    await area.blocks(*[(x, 3, 0, "farmland") for x in xs], *[(x, 4, 0, "wheat", {"age": 7}) for x in xs])
    p = await make_player(area, 0, 0)
    events, dug = await dug_while(server, area, p, f"await harvestWheat(bot, new Vec3({area.x0 + 10}, 4, 0))")
    assert errors(events) == []
    assert dug == list(xs)


async def test_a_target_replanted_before_the_bot_gets_there_is_still_broken(server, area, make_player):
    # ripeness picks the targets; on arrival upstream's collectblock checks only the block's type, so a
    # crop someone harvested and replanted meanwhile is broken too (and a picked bush right-clicked)
    await area.blocks(*[(x, 3, 0, "farmland") for x in (2, 10)], *[(x, 4, 0, "wheat", {"age": 7}) for x in (2, 10)])
    p = await make_player(area, 0, 0)
    q = server.control.subscribe()
    try:
        run = asyncio.ensure_future(p.run(f"await harvestWheat(bot, new Vec3({area.x0 + 2}, 4, 0))"))
        dug: list[int] = []
        while not dug:  # the near one first; then the far one is replanted before the bot gets there
            e = await asyncio.wait_for(q.get(), 20)
            if e["event"] == "block_dug":
                dug.append(e["pos"][0] - area.x0)
        await area.blocks((10, 4, 0, "wheat", {"age": 0}))
        events = await run
        await asyncio.sleep(0.3)
        dug += [e["pos"][0] - area.x0 for e in (q.get_nowait() for _ in range(q.qsize())) if e["event"] == "block_dug"]
    finally:
        server.control.unsubscribe(q)
    assert errors(events) == []
    assert dug == [2, 10]
    assert "Harvested 2 wheat" in chats_by(events, p.name)  # the targets found, as upstream's chat
    assert (await server.get_block(pos=area.at(10, 4, 0)))["name"] == "air"


async def test_wait_signal_calls_its_task_with_bot_and_chats_when_it_happens(server, area, make_player):
    p = await make_player(area, 0, 0)
    events = await p.run(
        "let given = null\n"
        "const got = await waitSignal(bot, async (b) => { given = b; await bot.waitForTicks(30); bot.chat('task done') }, 300)\n"
        "bot.chat(got === false && given === bot ? 'task had bot' : 'task had ' + typeof given)"
    )
    assert errors(events) == []
    # the timeout is announced when it happens, before the longer task ends
    assert chats_by(events, p.name) == ["[waiting signal]", "[signal timeout]", "task done", "task had bot"]


async def test_mine_block_turns_to_the_block_at_head_speed_before_digging(server, area, make_player):
    # upstream's collectblock digs with mineflayer's default look: the head turns at 3 rad/s (about
    # 20 ticks for half a turn), so the server sees the yaw pass through the quarter turns; a forced
    # look jumps from facing north (180°) to facing the block south of the bot (0°) in one packet
    await area.blocks((0, 4, 2, "slime_block"))
    p = await make_player(area, 0, 0)
    await p.run(f"await bot.lookAt(new Vec3({area.x0 + 0.5}, 5.6, -20), true)\nawait bot.waitForTicks(5)")
    await server.replay_frame(start=True)
    mining = asyncio.create_task(p.run("await mineBlock(bot, 'slime_block', 1)"))
    yaws = []
    while not mining.done():
        frame = await server.replay_frame()
        yaws += [pl[4] % 360 for pl in frame["players"] if pl[0] == p.name]
        await asyncio.sleep(0.01)
    await server.replay_frame(stop=True)
    assert errors(await mining) == []
    assert await count(server, p.name, "slime_block") == 1
    assert abs(yaws[0] - 180) < 10, yaws[:5]
    assert any(30 < y < 150 or 210 < y < 330 for y in yaws), sorted(set(yaws))


async def test_an_unreachable_drop_is_given_up_once(server, area, make_player):
    # a slime block on a 3 × 3 roof 3 blocks up drops onto the roof, out of reach and out of pickup
    # range; collectblock tries it once (10 s) however often mineflayer reports the item
    roof = [(x, 6, z, "mushroom_stem") for x in (7, 8, 9) for z in (3, 4, 5)]
    await area.blocks(*roof, (8, 7, 4, "slime_block"))
    p = await make_player(area, 6, 4)
    events = await p.run("await mineBlock(bot, 'slime_block', 1)")
    assert errors(events) == []
    said = chats_by(events, p.name)
    assert said.count("Failed to pickup item! Skip it!") == 1, said
    assert "Mined 1 slime_block" in said
