"""Item pickup as in vanilla 1.16: the reach is the player's box grown by 1 horizontally and 0.5
vertically, an item waits out its pickup delay, and when two players touch an item in the same tick
neither the join order nor the side decides who gets it."""

from __future__ import annotations

import asyncio

import pytest

from tests.server.conftest import count, equals, on_ground, wait_until
from tests.support.node_script import run_node_script

BOX_SCRIPT = r"""
const { touches, shuffled } = require(process.argv[1] + '/server/pickup.js')
const { PICKUP } = require(process.argv[1] + '/server/tables.js')
const p = { x: 0.5, y: 4, z: 0.5 }
const at = (dx, dy, dz) => touches(p, { x: p.x + dx, y: p.y + dy, z: p.z + dz })
let seed = 7
const rnd = () => { seed = (seed * 16807) % 2147483647; return seed / 2147483647 }
const firsts = { a: 0, b: 0, c: 0 }
for (let i = 0; i < 30000; i++) firsts[shuffled(['a', 'b', 'c'], rnd)[0]]++
console.log(JSON.stringify({
  table: PICKUP,
  centre: at(0, 0, 0),
  x_in: at(1.42, 0, 0), x_out: at(1.43, 0, 0), z_in: at(0, 0, -1.42), z_out: at(0, 0, -1.43),
  corner_in: at(1.4, 0, 1.4), corner_sphere_only: at(1.5, 0, 0.2),
  below_in: at(0, -0.74, 0), below_out: at(0, -0.76, 0),
  above_in: at(0, 2.29, 0), above_out: at(0, 2.31, 0),
  firsts
}))
"""


def test_pickup_box_is_the_player_box_grown_by_one_and_a_half():
    out = run_node_script(BOX_SCRIPT)
    assert out["table"]["reach"] == {"horizontal": 1.0, "vertical": 0.5}
    assert out["table"]["delayTicks"] == {"block": 10, "mob": 10, "toss": 40}
    # half width 0.3 + reach 1.0 + item half width 0.125 = 1.425 on x and z
    assert out["centre"] and out["x_in"] and out["z_in"] and out["corner_in"]
    assert not out["x_out"] and not out["z_out"]
    # flying-squid's old 1.75-block sphere reached this; vanilla's box does not
    assert not out["corner_sphere_only"]
    # below: reach 0.5 + item height 0.25; above: player height 1.8 + reach 0.5
    assert out["below_in"] and not out["below_out"]
    assert out["above_in"] and not out["above_out"]


def test_the_per_tick_order_favours_nobody():
    firsts = run_node_script(BOX_SCRIPT)["firsts"]
    assert all(9000 < n < 11000 for n in firsts.values()), firsts


@pytest.mark.parametrize("first", ["alice", "bob"])
async def test_two_players_equally_near_share_contested_items_whatever_the_join_order(arena, bots, area, first):
    alice, bob = bots
    await area.put(alice, 1, 4)
    await area.put(bob, 3, 4)
    order = [first, "bob" if first == "alice" else "alice"]
    assert (await arena.player_order(names=order))[:2] == order
    drops = 40
    # one drop between them every 2 ticks, so every drop is decided in a tick of its own
    for i in range(drops):
        await arena.spawn_item(item="stick", pos=area.at(2.5, 4, 4.5), delay_ticks=10 + 2 * i)
    assert await wait_until(lambda: equals(on_ground(arena, "stick", area.at(2.5, 4, 4.5)), 0), timeout=20)
    got = {n: await count(arena, n, "stick") for n in ("alice", "bob")}
    assert sum(got.values()) == drops
    # with a fair coin, P(one side gets <= 8 of 40) < 1e-4; the old pickup gave all 40 to `first`
    assert 8 < got["alice"] < 32, got


async def test_an_item_outside_the_vanilla_box_stays_on_the_ground(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 2, 8)
    # 1.5 blocks away on x: inside the old 1.75 sphere, outside the box (1.425)
    await arena.spawn_item(item="feather", pos=area.at(4.0, 4, 8.5), delay_ticks=0)
    await asyncio.sleep(1.5)
    assert await count(arena, "alice", "feather") == 0
    assert await on_ground(arena, "feather", area.at(4.0, 4, 8.5)) == 1
    # 1.3 blocks away: inside the box
    await arena.spawn_item(item="bone", pos=area.at(3.8, 4, 8.5), delay_ticks=0)
    assert await wait_until(lambda: equals(count(arena, "alice", "bone"), 1))


async def test_an_item_is_not_picked_up_before_its_delay(arena, bots, area):
    alice, _ = bots
    await area.put(alice, 2, 12)
    await arena.spawn_item(item="string", pos=area.at(2.5, 4, 12.5), delay_ticks=40)
    await asyncio.sleep(1.0)  # at most 20 ticks have passed, whatever the load
    assert await count(arena, "alice", "string") == 0
    assert await wait_until(lambda: equals(count(arena, "alice", "string"), 1))


async def test_spawn_item_and_player_order_refuse_bad_input(arena, bots, area):
    for args, fragment in [
        ({"item": "stik", "pos": [0, 4, 0]}, "unknown item 'stik'"),
        ({"item": "stick", "pos": [0, 4, 0], "count": 65}, "count must be an integer 1..64"),
        ({"item": "stick", "pos": [0, 4, 0], "delay_ticks": -1}, "delay_ticks must be"),
    ]:
        with pytest.raises(Exception, match=fragment):
            await arena.spawn_item(**args)
    with pytest.raises(Exception, match="no player named"):
        await arena.player_order(names=["alice", "nobody"])
    with pytest.raises(Exception, match="distinct"):
        await arena.player_order(names=["alice", "alice"])


async def test_an_item_picked_up_as_it_falls_leaves_no_entity_behind_in_the_bots(arena, bots, area):
    """flying-squid sent a falling item's move after its pickup had destroyed it (its entity tick awaits
    the physics): mineflayer made a nameless entity of the id, kept for the match (every bot, at every
    such pickup of a match: js/server/plugins/entities.js)."""
    alice, bob = bots
    await area.put(alice, 4, 4)
    await area.put(bob, 6, 4)
    drops = 12
    for _ in range(drops):  # at the top of alice's reach, so it is picked up in its first ticks of falling
        await arena.spawn_item(item="wheat_seeds", pos=area.at(4.5, 6.2, 4.5), delay_ticks=0)
        await asyncio.sleep(0.15)
    assert await wait_until(lambda: equals(count(arena, "alice", "wheat_seeds"), drops))
    await asyncio.sleep(0.5)  # anything the server still sent of them has arrived
    nameless = "return Object.values(bot.entities).filter(e => !e.name).length"
    assert [await b.eval(nameless) for b in (alice, bob)] == [0, 0]
