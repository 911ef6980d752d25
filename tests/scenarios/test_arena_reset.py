"""Putting an arena back in place restores it exactly: blocks, chests, furnaces, mobs, dropped items."""

from __future__ import annotations

import pytest

from pillagerbench.scenarios import make_scenario


async def snapshot(server, arena):
    (x0, _, z0), (x1, y1, z1) = arena.box
    return {
        "blocks": await server.scan([x0, 1, z0], [x1, y1, z1]),
        "chests": {p: await server.get_chest(pos=list(p)) for p in arena.chests},
        "furnaces": {p: await server.get_furnace(pos=list(p)) for p in arena.furnaces},
        "mobs": sorted((m["name"], tuple(round(v, 1) for v in m["pos"])) for m in await server.mobs()),
        "items": await server.items(),
    }


@pytest.mark.parametrize("name", ["mushroom_war", "dash_and_dine"])
async def test_reset_restores_the_arena_exactly(server, name):
    sc = make_scenario(name)
    arena = sc.arena
    await arena.build(server)
    before = await snapshot(server, arena)
    assert len(before["blocks"]) > len(arena.blocks)  # the ground is in the scan too
    # wreck it: dig, place, loot chests, light a furnace, kill mobs, drop items
    first = arena.blocks[0]
    await server.set_blocks(
        blocks=[[*first[:3], "air"], [first[0], 9, first[2], "stone"], [first[0] + 1, 3, first[2], "air"]]
    )
    for p in arena.chests:
        await server.set_chest(pos=list(p), items={"dirt": 1})
    for p in arena.furnaces:
        await server.set_furnace(pos=list(p), input=["potato", 1])
    await server.remove_entities()
    await server.summon(mob="pig", pos=[0.5, 4, 0.5])
    await server.fill([-3, 4, -3], [-2, 5, -2], "slime_block")
    assert await snapshot(server, arena) != before
    await arena.build(server)
    after = await snapshot(server, arena)
    assert after == before
