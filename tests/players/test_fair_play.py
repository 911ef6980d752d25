"""The rows of issue 12's table, forged from sandboxed agent code: the server refuses what a
vanilla server refuses, its state stays unchanged, and the refusal reaches the player's own events
(an onChat line "[refused] ...") as well as the control channel."""

from __future__ import annotations

import json
import os

from pillagerbench.players.events import chat_log, errors
from pillagerbench.scenarios import make_scenario
from tests.players.conftest import count
from tests.support.cli import run_cli
from tests.support.server_clock import caught_up, chat_code


async def _refused(server, q, player) -> list[dict]:
    """The `refused` events in `q`, once the server has handled everything `player` sent so far."""
    await caught_up(server, player.name, lambda text: player.run(chat_code(text)))
    return [e for e in (q.get_nowait() for _ in range(q.qsize())) if e.get("event") == "refused"]


async def _pos(server, name):
    return next(p["pos"] for p in await server.players() if p["name"] == name)


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
        got = await _refused(server, q, p)
    finally:
        server.control.unsubscribe(q)
    assert await _pos(server, p.name) == start
    assert (await server.get_block(pos=area.at(-9, 4, 6)))["name"] == "red_mushroom_block"
    assert got[0]["action"] == "move" and "moved too quickly" in got[0]["reason"], got
    assert any(line.startswith("[refused] move: moved too quickly") for line in chat_log(events))


async def test_rising_into_the_air_is_put_back(server, area, make_player):
    p = await make_player(area, 0, 0)
    q = server.control.subscribe()
    try:
        events = await p.run(
            "bot.entity.position.set(bot.entity.position.x, 20, bot.entity.position.z)\nawait bot.waitForTicks(40)"
        )
        got = await _refused(server, q, p)
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
        got = await _refused(server, q, p)
    finally:
        server.control.unsubscribe(q)
    assert (await server.get_block(pos=area.at(15, 4, 6)))["name"] == "red_mushroom_block"
    assert [g["action"] for g in got] == ["dig"] and "too far to dig red_mushroom_block" in got[0]["reason"]
    assert any(line.startswith("[refused] dig: too far") for line in chat_log(events))


async def test_a_chest_out_of_reach_cannot_be_opened(server, area, make_player):
    p = await make_player(area, 0, 0)
    await area.blocks((10, 4, 3, "chest"))  # 10.7 blocks away
    chest = area.at(10, 4, 3)
    await server.set_chest(pos=chest, items={"gold_nugget": 64})
    q = server.control.subscribe()
    try:
        events = await p.run(
            f"const v = new Vec3({chest[0]}, 4, 3)\n"
            "for (let i = 0; i < 40 && bot.blockAt(v).name !== 'chest'; i++) await bot.waitForTicks(1)\n"
            "const c = await bot.openContainer(bot.blockAt(v))\n"
            "await c.withdraw(mcData.itemsByName.gold_nugget.id, null, 64)",
            timeout=30,
        )
        got = await _refused(server, q, p)
    finally:
        server.control.unsubscribe(q)
    assert await server.get_chest(pos=chest) == {"gold_nugget": 64}
    assert await count(server, p.name, "gold_nugget") == 0
    assert [g["action"] for g in got] == ["use_block"] and "too far to use chest" in got[0]["reason"], (
        got,
        errors(events),
    )
    assert any(line.startswith("[refused] use_block") for line in chat_log(events))


async def test_honest_primitives_trip_nothing(server, area, make_player):
    p = await make_player(area, 0, 0, {"dirt": 2}, primitives=["mineBlock", "placeItem", "useChest"])
    await area.blocks((8, 4, 4, "red_mushroom_block"), (9, 4, -4, "chest"))
    await server.set_chest(pos=area.at(9, 4, -4), items={"gold_nugget": 5})
    q = server.control.subscribe()
    try:
        events = await p.run(
            f"const seen = [[new Vec3({area.x0 + 8}, 4, 4), 'red_mushroom_block'], [new Vec3({area.x0 + 9}, 4, -4), 'chest']]\n"
            "for (let i = 0; i < 100 && !seen.every(([v, name]) => bot.blockAt(v)?.name === name); i++)"
            " await bot.waitForTicks(1)\n"  # the blocks just set reach the bot a moment later
            f"await mineBlock(bot, 'red_mushroom_block', 1)\nawait placeItem(bot, 'dirt', new Vec3({area.x0 + 3}, 4, 0))\n"
            f"await getItemFromChest(bot, new Vec3({area.x0 + 9}, 4, -4), {{gold_nugget: 5}})",
            timeout=60,
        )
        got = await _refused(server, q, p)
    finally:
        server.control.unsubscribe(q)
    said = (errors(events), chat_log(events), got)  # what the run said, should a primitive fail
    assert (await server.get_block(pos=area.at(8, 4, 4)))["name"] == "air", said
    assert (await server.get_block(pos=area.at(3, 4, 0)))["name"] == "dirt", said
    assert await count(server, p.name, "gold_nugget") == 5
    assert got == []


FAR_DIGGER = '''
from pillagerbench.teams import Team


class FarDigger(Team):
    """Its first player digs the ground 12 blocks away once (refused); the other does nothing."""

    name = "far_digger"
    scenarios = ("mushroom_war",)

    async def play(self, ctx):
        first = next(iter(ctx.players.values()))
        await first.run(
            "const p = bot.entity.position.floored()\\n"
            "await bot.dig(bot.blockAt(p.offset(12, -1, 0)), true).catch(() => {})\\nawait bot.waitForTicks(5)"
        )
'''


def test_an_episodes_record_counts_each_players_refusals(tmp_path):
    (tmp_path / "far_digger.py").write_text(FAR_DIGGER)
    run = tmp_path / "run"
    proc = run_cli(
        tmp_path,
        "run",
        "scenario=mushroom_war",
        "red=far_digger:FarDigger",
        "blue=do_nothing",
        "episode_length=6",
        "clock=lockstep",  # a rule's test, on game time
        f"run_dir={run}",
        env={"PYTHONPATH": os.pathsep.join(filter(None, [str(tmp_path), os.environ.get("PYTHONPATH")]))},
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    # the episode used (one spoiled on our side, stalled by a loaded machine, is played again before it)
    records = [json.loads(line) for line in (run / "episodes.jsonl").read_text().splitlines()]
    rec = records[-1]
    first = make_scenario("mushroom_war").side("red").player_names[0]
    assert rec["status"] == "ok" and rec["refusals"] == {first: 1}, rec
    world = [json.loads(line) for line in open(run / f"episode_{rec['episode']:03d}" / "world_events.jsonl")]
    [refused] = [e for e in world if e["event"] == "refused"]
    assert (
        refused["player"] == first and refused["action"] == "dig" and "too far to dig grass_block" in refused["reason"]
    )
