"""The scenarios' rules, run by their game masters against the real server."""

from __future__ import annotations

from pillagerbench.scenarios import make_scenario
from pillagerbench.scenarios.dash_and_dine import REWARDS, Y, upstream_round
from pillagerbench.scenarios.dash_and_dine_layout import FACING as SIDES
from pillagerbench.scenarios.dash_and_dine_layout import PAPER_LAYOUT as DD_PAPER
from pillagerbench.scenarios.mushroom_war import AREA_RADIUS, caps, slime, upstream_multiplier
from pillagerbench.scenarios.mushroom_war_layout import PAPER_LAYOUT as MW_PAPER
from tests.scenarios.conftest import Always
from tests.support.bots import TestBot

RED = MW_PAPER.red
RED_CENTER = (RED.center[0], Y, RED.center[1])
EGG_CHEST = DD_PAPER.poi("egg_chest")


async def blocks_named(server, name, center):
    return {tuple(b[:3]) for b in await server.find_blocks(names=[name], center=list(center), radius=AREA_RADIUS)}


async def test_mushrooms_regrow_only_while_the_area_holds_at_most_7_slime(server):
    sc = make_scenario("mushroom_war")
    await sc.arena.build(server)
    red_caps = caps(RED)
    await server.set_blocks(blocks=[[*p, "air"] for p in red_caps[:5]])
    gm = sc.game_master(server, Always(0.0))  # every chance happens
    await gm.start()
    # 15 slime blocks in the red area: too dirty, nothing regrows (slime respawn is a no-op: all present);
    # as upstream's, the game master starts with both teams dirty, so it says nothing about it
    await gm.step()
    assert len(await blocks_named(server, "red_mushroom_block", RED_CENTER)) == 10
    assert gm.log[0] == {"chat": "starting cleanup scenario..."}
    assert not any("dirty" in e.get("chat", "") or "clean!" in e.get("chat", "") for e in gm.log)
    # clean 8 of them: 7 left, the area counts as clean and every missing cap regrows
    gm_clean = sc.game_master(server, Always(0.99))  # no slime comes back while we check
    await gm_clean.start()
    await server.set_blocks(blocks=[[*p, "air"] for p in slime(RED)[:8]])
    await gm_clean.step()
    assert len(await blocks_named(server, "slime_block", RED_CENTER)) == 7
    assert len(await blocks_named(server, "red_mushroom_block", RED_CENTER)) == 10  # p=0.99 draws: no regrowth
    gm_sure = sc.game_master(server, Always(0.05))  # below P_REGROW (0.1), above P_SLIME (0.02)
    await gm_sure.start()
    await gm_sure.step()
    assert {"chat": "Team 0 is clean!"} in gm_sure.log  # upstream's naming: red 0, blue 1
    assert await blocks_named(server, "red_mushroom_block", RED_CENTER) == set(red_caps)
    assert len(await blocks_named(server, "slime_block", RED_CENTER)) == 7  # 0.05 > P_SLIME: no respawn
    await server.set_blocks(blocks=[[*p, "slime_block"] for p in slime(RED)])
    await gm_sure.step()
    assert gm_sure.log[-1] == {"chat": "Team 0 is too dirty!"}


async def test_slime_respawns_at_its_original_positions(server):
    sc = make_scenario("mushroom_war")
    await sc.arena.build(server)
    await server.set_blocks(blocks=[[*p, "air"] for p in slime(RED)])
    gm = sc.game_master(server, Always(0.01))  # below P_SLIME
    await gm.start()
    await gm.step()
    assert await blocks_named(server, "slime_block", RED_CENTER) == set(slime(RED))


async def test_mushroom_war_score_is_own_colour_mushrooms_held(server):
    sc = make_scenario("mushroom_war")
    async with TestBot(server.port, "Ryn"), TestBot(server.port, "Byte"):
        await server.set_inventory(player="Ryn", items={"red_mushroom": 3, "brown_mushroom": 5})
        await server.set_inventory(player="Byte", items={"brown_mushroom": 2})
        gm = sc.game_master(server, Always(0.99))
        await gm.start()
        assert await gm.scores() == {"red": 3.0, "blue": 2.0}
        await server.take(player="Ryn", item="red_mushroom", count=2)
        assert (await gm.scores())["red"] == 1.0  # giving away or dropping lowers the score


async def test_dash_and_dine_lock_in_first_three_types_by_whoever_gives(server):
    sc = make_scenario("dash_and_dine")
    async with TestBot(server.port, "Red_Server"), TestBot(server.port, "Blue_Server"):
        gm = sc.game_master(server, Always(0.99))
        await gm.start()
        # an opponent's gift locks potato into the red server; then three more types arrive
        await server.set_inventory(player="Red_Server", items={"potato": 2, "stick": 5})
        await gm.step()
        assert gm.locked["red"] == ["potato"]
        assert gm.points["red"] == 2 * REWARDS["potato"]
        assert await server.inventory(player="Red_Server") == []  # emptied, sticks lost too
        await server.set_inventory(player="Red_Server", items={"bread": 1, "beef": 2, "cake": 1})
        await gm.step()
        assert len(gm.locked["red"]) == 3 and gm.locked["red"][0] == "potato"
        first_two = gm.locked["red"][1:]
        assert set(first_two) < {"bread", "beef", "cake"}
        expected = 2 * REWARDS["potato"] + sum({"bread": 1, "beef": 2, "cake": 1}[i] * REWARDS[i] for i in first_two)
        assert abs(gm.points["red"] - expected) < 1e-9
        assert gm.log[0] == {"chat": "starting dining scenario..."}
        assert any("Locked-in potato as a submission item for team_red" == e.get("chat") for e in gm.log)
        # raw beef scores (upstream's keys never matched it)
        await server.set_inventory(player="Blue_Server", items={"beef": 1})
        await gm.step()
        assert gm.points["blue"] == REWARDS["beef"] == 4.8
        assert (await gm.scores())["blue"] == 4.8


async def test_mushroom_war_upstream_score_counts_held_mushrooms_once_per_run_started(server):
    # upstream: each run started a counter adding what the player holds, from 0, that never stopped.
    # By hand, Ryn holds 2 then 3; Raze 4; Byte 1. Ryn has started 1 run, then 3; Raze none (do_nothing
    # ran one step upstream: counted once); Byte 2.
    sc = make_scenario("mushroom_war")
    async with TestBot(server.port, "Ryn"), TestBot(server.port, "Raze"), TestBot(server.port, "Byte"):
        await server.set_inventory(player="Ryn", items={"red_mushroom": 2})
        await server.set_inventory(player="Raze", items={"red_mushroom": 4, "brown_mushroom": 9})
        await server.set_inventory(player="Byte", items={"brown_mushroom": 1})
        gm = sc.game_master(server, Always(0.99))
        await gm.start()
        assert await gm.upstream_scores({"Ryn": 1, "Byte": 2}) == {"red": 2 * 1 + 4 * 1, "blue": 1 * 2}
        await server.set_inventory(player="Ryn", items={"red_mushroom": 3})
        assert await gm.upstream_scores({"Ryn": 3, "Byte": 2}) == {"red": 3 * 3 + 4, "blue": 2}
        assert await gm.scores() == {"red": 7.0, "blue": 1.0}  # clean: what they hold


async def test_dash_and_dine_upstream_score_rounds_each_scan(server):
    # scans worth 7.2 (3 berries), 2.4 (1 berry), 15.8 (1 bread + 2 berries) by hand:
    # upstream adds round(7.2) + round(2.4) + round(15.8) = 7 + 2 + 16 = 25; clean 25.4
    sc = make_scenario("dash_and_dine")
    async with TestBot(server.port, "Red_Server"), TestBot(server.port, "Blue_Server"):
        gm = sc.game_master(server, Always(0.99))
        await gm.start()
        for items in ({"sweet_berries": 3}, {"sweet_berries": 1}, {"bread": 1, "sweet_berries": 2}):
            await server.set_inventory(player="Red_Server", items=items)
            await gm.step()
        assert REWARDS["sweet_berries"] == 2.4 and REWARDS["bread"] == 11
        assert (await gm.scores())["red"] == 25.4
        assert await gm.upstream_scores({}) == {"red": 25.0, "blue": 0.0}


def test_upstream_rounding_is_javascripts_halves_up():
    assert [upstream_round(x) for x in (0.4, 0.5, 2.5, 7.2, 15.8)] == [0, 1, 3, 7, 16]


def test_upstream_counts_a_player_once_to_ten_times():
    runs = {"Ryn": 0, "Raze": 4, "Byte": 25}
    assert [upstream_multiplier(runs, n) for n in ("Ryn", "Raze", "Byte", "Blink")] == [1, 4, 10, 1]


async def test_dash_and_dine_world_as_the_reference(server):
    """14 chickens laying into an egg chest that starts empty, one cow, creative (unkillable) servers."""
    sc = make_scenario("dash_and_dine")
    await sc.arena.build(server)
    mobs = await server.mobs()
    assert sum(m["name"] == "chicken" for m in mobs) == 14
    assert sum(m["name"] == "cow" for m in mobs) == 1
    assert await server.get_chest(pos=list(EGG_CHEST)) == {}
    assert all(p.gamemode == "creative" for p in sc.extra_players)
    assert {p.gamemode for s in sc.sides for p in s.players} == {"survival"}
    # per-farm yields, the random tick speed, 14 chickens and the reference's food rows, no added hints
    text = sc.description()
    for fact in (
        "random tick speed is 200",
        "14 chickens",
        "about 160 sweet berries per minute",
        "poisonous_potato",
        "- sugar_cane: farmed: 0",
    ):
        assert fact in text
    assert "whoever" not in text and "empties" not in text


async def test_dash_and_dine_stems_as_the_builders_seeds_each_free_on_four_sides(server):
    """2 melon and 4 pumpkin stems (the builder's statistics), each with its fruit and three free
    sides over soil, so no stem's fruit can take another stem's side but where the farm shares it."""
    sc = make_scenario("dash_and_dine")
    await sc.arena.build(server)
    centre = (-15, Y, -1)
    for fruit, n in (("melon", 2), ("pumpkin", 4)):
        stems = await blocks_named(server, f"attached_{fruit}_stem", centre)
        assert len(stems) == n
        for x, y, z in stems:
            sides = [await server.get_block(pos=[x + dx, y, z + dz]) for dx, dz in SIDES.values()]
            assert sorted(b["name"] for b in sides) == sorted([fruit, "air", "air", "air"])
            soils = [await server.get_block(pos=[x + dx, y - 1, z + dz]) for dx, dz in SIDES.values()]
            assert {b["name"] for b in soils} <= {"farmland", "grass_block", "dirt"}
