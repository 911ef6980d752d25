"""Fair play, forged from a raw protocol client (the test driver's `bot._client`, which agent code
cannot reach): every limit of docs/fair-play.md leaves the server's state unchanged and reports a
`refused` event naming the player, the action and the reason."""

from __future__ import annotations

from contextlib import asynccontextmanager

from tests.server.conftest import count
from tests.support.server_clock import caught_up, chat_code


@asynccontextmanager
async def refusals(arena, bot):
    """Collects the server's `refused` events while the block runs (a list, filled on exit, once the
    server has handled everything `bot` sent in the block: a late refusal is in it)."""
    q = arena.control.subscribe()
    got: list[dict] = []
    try:
        yield got
        await caught_up(arena, bot.username, lambda text: bot.eval(chat_code(text)))
    finally:
        arena.control.unsubscribe(q)
        got.extend(e for e in (q.get_nowait() for _ in range(q.qsize())) if e.get("event") == "refused")


async def block(arena, pos) -> str:
    return (await arena.get_block(pos=pos))["name"]


def raw(packet: str, fields: str) -> str:
    return f"bot._client.write('{packet}', {fields})"


async def test_dig_out_of_reach_is_refused(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 0, 0)
    far = area.at(10, 4, 0)
    await arena.set_block(pos=far, block="dirt")
    async with refusals(arena, alice) as got:
        await alice.eval(
            raw("block_dig", "{status: 0, location: new Vec3(%d, 4, 0), face: 1}") % far[0]
            + "\nawait sleep(900)\n"
            + raw("block_dig", "{status: 2, location: new Vec3(%d, 4, 0), face: 1}") % far[0]
            + "\nawait sleep(200)"
        )
    assert await block(arena, far) == "dirt"
    assert len(got) == 1, got  # the finish of a refused start is not counted twice
    assert got[0]["player"] == "alice" and got[0]["action"] == "dig" and "too far to dig dirt" in got[0]["reason"]


async def test_dig_faster_than_dig_time_is_refused(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 0, 0)
    near = area.at(1, 4, 0)
    await arena.set_block(pos=near, block="stone")  # 7.5 s by hand
    async with refusals(arena, alice) as got:
        await alice.eval(
            raw("block_dig", "{status: 0, location: new Vec3(%d, 4, 0), face: 1}") % near[0]
            + "\nawait sleep(300)\n"
            + raw("block_dig", "{status: 2, location: new Vec3(%d, 4, 0), face: 1}") % near[0]
            + "\nawait sleep(200)"
        )
        await alice.eval(
            raw("block_dig", "{status: 2, location: new Vec3(%d, 4, 0), face: 1}") % near[0] + "\nawait sleep(200)"
        )
    assert await block(arena, near) == "stone"
    assert [g["action"] for g in got] == ["dig", "dig"], got
    assert "broken too fast" in got[0]["reason"] and "without starting it" in got[1]["reason"]


async def test_honest_digging_passes(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 0, 0, {"wooden_shovel": 1})
    near = area.at(2, 4, 1)
    await area.set_block(near, "dirt", seen_by=alice)
    async with refusals(arena, alice) as got:
        await alice.eval(
            "await bot.equip(mcData.itemsByName.wooden_shovel.id, 'hand')\n"
            "await bot.dig(bot.blockAt(new Vec3(%d, 4, 1)), true)\nawait sleep(200)" % near[0]
        )
    assert await block(arena, near) == "air"
    assert got == []


async def test_place_out_of_reach_occupied_unsupported_or_into_a_player_is_refused(arena, bots, area):
    alice, bob = bots
    await area.put(alice, 0, 0, {"dirt": 10})
    await area.put(bob, 2, 0)
    x = area.x0
    await arena.set_blocks(blocks=[[x + 11, 3, 0, "grass_block"], [x + 1, 4, 2, "stone"], [x + 1, 5, 2, "stone"]])
    place = "bot._client.write('block_place', {hand: 0, location: new Vec3(%d, %d, %d), direction: %d, cursorX: 0.5, cursorY: 0.5, cursorZ: 0.5, insideBlock: false})\nawait sleep(250)"
    async with refusals(arena, alice) as got:
        await alice.eval("await bot.equip(mcData.itemsByName.dirt.id, 'hand')")
        await alice.eval(place % (x + 11, 3, 0, 1))  # 10.6 blocks away: top of far grass
        await alice.eval(place % (x + 1, 4, 2, 1))  # on top of a stone with a stone above it: occupied
        await alice.eval(place % (x + 1, 7, 0, 1))  # against air
        await alice.eval(place % (x + 2, 3, 0, 1))  # on the grass bob stands on: into bob
    assert await block(arena, [x + 11, 4, 0]) == "air"
    assert await block(arena, [x + 1, 5, 2]) == "stone"
    assert await block(arena, [x + 1, 8, 0]) == "air" and await block(arena, [x + 1, 7, 0]) == "air"
    assert await block(arena, [x + 2, 4, 0]) == "air"
    assert await count(arena, "alice", "dirt") == 10
    assert [g["action"] for g in got] == ["place"] * 4, got
    assert "too far to place against grass_block" in got[0]["reason"]
    assert (
        "stone is there" in got[1]["reason"]
        and "against" in got[2]["reason"]
        and "bob is in the way" in got[3]["reason"]
    )


async def test_chest_out_of_reach_cannot_be_used(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 0, 0)
    chest = area.at(10, 4, 3)
    await arena.set_block(pos=chest, block="chest")
    await arena.set_chest(pos=chest, items={"gold_nugget": 64})
    async with refusals(arena, alice) as got:
        await alice.eval(
            "bot._client.write('block_place', {hand: 0, location: new Vec3(%d, 4, 3), direction: 1, cursorX: 0.5,"
            " cursorY: 0.5, cursorZ: 0.5, insideBlock: false})\nawait sleep(400)\n"
            "bot._client.write('window_click', {windowId: 1, slot: 0, mouseButton: 1, action: 1, mode: 1, item: {present: false}})\n"
            "await sleep(300)" % chest[0]
        )
    assert await arena.get_chest(pos=chest) == {"gold_nugget": 64}
    assert await count(arena, "alice", "gold_nugget") == 0
    assert len(got) == 1 and got[0]["action"] == "use_block" and "too far to use chest" in got[0]["reason"]


async def test_open_chest_closes_when_its_player_goes_out_of_reach(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 0, 0)
    chest = area.at(2, 4, 0)
    await arena.set_block(pos=chest, block="chest")
    await arena.set_chest(pos=chest, items={"gold_nugget": 64})
    await alice.eval(
        "const at = new Vec3(%d, 4, 0)\n"
        "for (let i = 0; i < 100 && bot.blockAt(at)?.name !== 'chest'; i++) await sleep(50)  // the block update\n"
        "global.c = await bot.openContainer(bot.blockAt(at))" % chest[0]
    )
    async with refusals(arena, alice) as got:
        await arena.teleport(player="alice", pos=area.at(12.5, 4, 0.5))
        await alice.eval(
            "await sleep(500)\nbot._client.write('window_click', {windowId: global.c.id, slot: 0, mouseButton: 1, action: 2,"
            " mode: 1, item: {present: false}})\nawait sleep(300)\nreturn bot.currentWindow ? bot.currentWindow.id : null"
        )
    assert await arena.get_chest(pos=chest) == {"gold_nugget": 64}
    assert await count(arena, "alice", "gold_nugget") == 0
    closed = [g for g in got if g["action"] == "use_block"]
    assert len(closed) == 1 and "walked out of reach of the chest" in closed[0]["reason"], got


async def test_attack_out_of_reach_is_refused_and_the_cooldown_scales_damage(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 0, 0, {"iron_sword": 1})
    far = await arena.summon(mob="cow", pos=area.at(9.5, 4, 0.5))
    near = await arena.summon(mob="cow", pos=area.at(2.5, 4, 0.5))
    await alice.eval(
        "for (let i = 0; i < 60 && !(bot.entities[%d] && bot.entities[%d]); i++) await sleep(50)" % (far, near)
    )
    health = lambda mobs, i: next(m["health"] for m in mobs if m["id"] == i)  # noqa: E731
    async with refusals(arena, alice) as got:
        await alice.eval(
            "await bot.equip(mcData.itemsByName.iron_sword.id, 'hand')\nawait sleep(1000)\n"
            "bot._client.write('use_entity', {target: %d, mouse: 1, sneaking: false})\nawait sleep(200)" % far
        )
        # a full-strength hit (12.5 ticks after the equip), then one at once: 6, then 6 * (0.2 + 0.8 * s^2)
        # with s = (ticks since the first hit + 0.5) / 12.5: 0.5 / 12.5, or 1.5 / 12.5 when a server tick
        # falls between the two packets (vanilla's getAttackStrengthScale(0.5))
        await alice.eval(
            "bot._client.write('use_entity', {target: %d, mouse: 1, sneaking: false})\n"
            "bot._client.write('use_entity', {target: %d, mouse: 1, sneaking: false})\nawait sleep(300)" % (near, near)
        )
    mobs = await arena.mobs()
    assert health(mobs, far) == 10
    second = 10 - 6 - health(mobs, near)
    assert any(abs(second - 6 * (0.2 + 0.8 * ((k + 0.5) / 12.5) ** 2)) < 0.01 for k in (0, 1)), second
    assert len(got) == 1 and got[0]["action"] == "attack" and "too far to attack cow" in got[0]["reason"]
    await arena.remove_entities()


MOVE = "bot._client.write('position', {x: %f, y: %f, z: %f, onGround: true})"


async def moves(bot, code: str) -> None:
    """Forge position packets with the bot's own physics off (so it sends none of its own)."""
    await bot.eval(
        "bot.physicsEnabled = false\nawait sleep(300)\ntry {\n%s\n} finally { await sleep(300); bot.physicsEnabled = true }"
        % code
    )


async def test_moves_beyond_the_limits_are_put_back(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 0, 0)
    x, z = area.x0 + 0.5, 0.5
    pos = lambda: next(p["pos"] for p in players if p["name"] == "alice")  # noqa: E731
    async with refusals(arena, alice) as got:
        await moves(alice, MOVE % (x + 16, 4, z + 6))  # 17 blocks in one move
        players = await arena.players()
        assert pos() == [x, 4, z]
        await moves(alice, MOVE % (x, 20, z))  # 16 up
        players = await arena.players()
        assert pos() == [x, 4, z]
        await moves(
            alice,
            # written at once, so no tick passes between them (the hover rule stays out of it)
            "for (let i = 1; i <= 6; i++) { %s }" % (MOVE % (x, 4, z)).replace("y: 4.000000", "y: 4 + 0.3 * i"),
        )
        players = await arena.players()
        assert pos()[1] <= 4 + 1.35, got
        await moves(
            alice,
            "for (let i = 1; i <= 20; i++) { %s }" % (MOVE % (x, 4, z)).replace("x: %f" % x, "x: %f + 0.9 * i" % x),
        )
    players = await arena.players()
    # 20 moves of 0.9 written at once: the allowance holds 10 blocks (and refills 10 blocks/s)
    assert pos()[0] < x + 12
    assert [g["action"] for g in got][:3] == ["move"] * 3, got
    assert "moved too quickly (17.1 blocks" in got[0]["reason"] and "put back" in got[0]["reason"]
    assert "moved up too quickly" in got[1]["reason"]
    assert "with nothing to stand on" in got[2]["reason"]
    assert any("faster than 10 blocks/s" in g["reason"] for g in got[3:]), got


async def test_hovering_is_brought_down(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 0, 0)
    x, z = area.x0 + 0.5, 0.5
    async with refusals(arena, alice) as got:
        # the client's own position says 4.9 and, without physics, stays there (it re-sends it every second)
        await moves(alice, "bot.entity.position.y = 4.9\nawait sleep(2600)")
    players = await arena.players()
    assert next(p["pos"] for p in players if p["name"] == "alice") == [x, 4, z], got
    assert len(got) == 1 and "hovered in the air" in got[0]["reason"] and "brought down" in got[0]["reason"], got


async def test_refusals_reach_the_player_as_chat(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 0, 0)
    far = area.at(10, 4, 0)
    await arena.set_block(pos=far, block="dirt")
    said = await alice.eval(
        "const lines = []\nconst on = (m) => lines.push(m)\nbot.on('messagestr', on)\n"
        + raw("block_dig", "{status: 0, location: new Vec3(%d, 4, 0), face: 1}") % far[0]
        + "\nawait sleep(400)\nbot.removeListener('messagestr', on)\nreturn lines"
    )
    assert any(line.startswith("[refused] dig: too far to dig dirt") for line in said), said


async def test_clicks_arriving_together_place_no_more_than_the_stack_holds(arena, bots, area):
    # flying-squid took the item off only after placing, so clicks sent together each placed one and
    # the stack went below zero (and went on placing); now each placement reserves its item at once
    alice, _ = bots
    await area.put(alice, 0, 0, {"dirt": 2})
    x = area.x0
    click = (
        "bot._client.write('block_place', {hand: 0, location: new Vec3(%d, 3, %d), direction: 1, cursorX: 0.5,"
        " cursorY: 0.5, cursorZ: 0.5, insideBlock: false})\n"
    )
    spots = [(x + 1, 1), (x + 2, 1), (x + 1, -1), (x + 2, -1), (x + 2, 0)]
    await alice.eval(
        "await bot.equip(mcData.itemsByName.dirt.id, 'hand')\n" + "".join(click % s for s in spots) + "await sleep(500)"
    )
    placed = [await block(arena, [sx, 4, sz]) for sx, sz in spots]
    assert placed.count("dirt") == 2, placed
    assert await count(arena, "alice", "dirt") == 0


async def test_placing_against_a_block_dug_a_moment_ago_is_a_silent_race(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 0, 0, {"dirt": 2})
    x = area.x0
    await area.set_block([x + 2, 4, 0], "oak_leaves", seen_by=alice)  # breaks in 0.3 s by hand
    async with refusals(arena, alice) as got:
        await alice.eval(
            "await bot.equip(mcData.itemsByName.dirt.id, 'hand')\nawait bot.dig(bot.blockAt(new Vec3(%d, 4, 0)), true)\n"
            "bot._client.write('block_place', {hand: 0, location: new Vec3(%d, 4, 0), direction: 1, cursorX: 0.5,"
            " cursorY: 0.5, cursorZ: 0.5, insideBlock: false})\nawait sleep(300)" % (x + 2, x + 2)
        )
    assert await block(arena, [x + 2, 5, 0]) == "air" and await block(arena, [x + 2, 4, 0]) == "air"
    assert got == []


async def test_refusal_chat_lines_are_capped_at_four_a_second_and_control_events_are_not(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 0, 0)
    digs = "".join(
        raw("block_dig", "{status: 0, location: new Vec3(%d, 4, %d), face: 1}") % (area.x0 + 10, z) + "\n"
        for z in range(8)
    )
    # the [refused] lines the bot gets up to its own chat's echo (the server writes them in order)
    told = (
        "const lines = []\nconst on = (m) => lines.push(m)\nbot.on('messagestr', on)\n%s"
        "bot.chat('%s')\nfor (let i = 0; i < 200 && !lines.some(l => l.endsWith('%s')); i++) await sleep(25)\n"
        "bot.removeListener('messagestr', on)\nreturn lines.filter(l => l.startsWith('[refused]'))"
    )
    await alice.eval("await sleep(1100)")  # the last refusal's second (from other tests) is over
    async with refusals(arena, alice) as got:
        burst = await alice.eval(told % (digs, "burst told", "burst told"))
    assert len(got) == 8 and all(g["action"] == "dig" for g in got), got  # every refusal reaches the control channel
    assert len(burst) == 4 and all(line.startswith("[refused] dig: too far to dig") for line in burst), burst
    await alice.eval("await sleep(1100)")  # a new second: the player is told again
    later = await alice.eval(told % (digs.splitlines()[0] + "\n", "later told", "later told"))
    assert len(later) == 1, later


async def test_creative_players_are_not_checked(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 0, 0)
    far = area.at(10, 4, 0)
    await arena.set_block(pos=far, block="dirt")
    x, z = area.x0 + 0.5, 0.5
    await arena.gamemode(player="alice", mode="creative")
    try:
        async with refusals(arena, alice) as got:
            await alice.eval(raw("block_dig", "{status: 0, location: new Vec3(%d, 4, 0), face: 1}") % far[0])
            # 17 blocks in one move (the bot's own physics off, its position set there: what it re-sends)
            await alice.eval(
                "bot.physicsEnabled = false\nawait sleep(300)\n%s\nbot.entity.position.set(%f, 4, %f)"
                % (MOVE % (x + 16, 4, z + 6), x + 16, z + 6)
            )
        players = await arena.players()
    finally:
        await alice.eval("bot.physicsEnabled = true")
        await arena.gamemode(player="alice", mode="survival")
    assert got == []
    assert await block(arena, far) == "air"  # a creative player breaks at once, from anywhere
    assert next(p["pos"] for p in players if p["name"] == "alice") == [x + 16, 4, z + 6]
