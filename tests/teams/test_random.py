"""The Random baseline: seeded choices, executable actions, and whole episodes in both scenarios (on the
lockstep clock: what it plays, not how fast)."""

from __future__ import annotations

import asyncio
import json

from pillagerbench.agents.code import parse_js
from pillagerbench.players import primitives as prim
from pillagerbench.scenarios import make_scenario
from pillagerbench.teams.random_team import ACTIONS, SEEDS, RandomActions
from tests.teams.conftest import play_series

DD = make_scenario("dash_and_dine").primitives
MW = make_scenario("mushroom_war").primitives

OBS = [
    {
        "voxels": ["grass_block", "wheat", "chest", "furnace"],
        "inventory": {"bucket": 1, "wheat_seeds": 3, "netherite_hoe": 1, "potato": 2},
        "status": {"position": {"x": -5.5, "y": 4, "z": -9.5}, "entities": {"cow": 3.2, "chicken": 8}},
        "nearbyChests": {"(-7, 4, -7)": {"bucket": 16}, "(-7, 4, 5)": "Unknown"},
    },
    {"voxels": ["grass_block"], "inventory": {}, "status": {"position": {"x": 0.5, "y": 4, "z": 0.5}, "entities": {}}},
    {
        "voxels": ["slime_block", "red_mushroom_block", "mushroom_stem", "grass_block"],
        "inventory": {"slime_block": 2},
        "status": {"position": {"x": -7.5, "y": 4, "z": -9.5}, "entities": {}},
    },
]


def sequence(seed, primitives, n=60, players=("Raze", "Red_Server")):
    gen = RandomActions(seed, primitives, players)
    return [gen.next(OBS[i % len(OBS)]) for i in range(n)]


def test_same_seed_same_actions_other_seed_other_actions():
    assert sequence(7, DD) == sequence(7, DD)
    assert sequence(7, DD) != sequence(8, DD)
    kinds = {a.kind for a in sequence(3, DD, n=400)}
    assert {
        "mineBlock",
        "craftItem",
        "milkCow",
        "getItemFromChest",
        "tillLand",
        "plantWheatSeeds",
        "bot.pathfinder.goto",
        "giveToPlayer",
        "smeltItem",
        "killMob",
    } <= kinds


def test_actions_use_only_the_scenarios_primitives_and_parse():
    allowed = set(prim.functions(list(MW)))
    for action in sequence(5, MW, n=300, players=("Raze",)):
        assert action.kind in allowed or action.kind.startswith("bot."), action
        parsed = parse_js(action.code)
        assert parsed.ok, (action.code, parsed.error)
        every = set(prim.functions())
        assert not [c for c in parsed.calls if c in every and c not in allowed], action.code


def test_every_kind_in_the_actions_table_is_a_primitive_or_a_bot_method_and_gets_drawn():
    kinds = [kind for kind, _, _ in ACTIONS]
    assert len(kinds) == len(set(kinds))
    assert [k for k in kinds if k not in set(prim.functions()) and not k.startswith("bot.")] == []
    # with every primitive and an observation where every check passes, each kind comes up, calling itself
    rich = {**OBS[0], "inventory": {**OBS[0]["inventory"], **{item: 1 for item in SEEDS.values()}}}
    gen = RandomActions(4, list(prim.MODULES), ("Raze",))
    actions = [gen.next(rich) for _ in range(3000)]
    assert {a.kind for a in actions} == set(kinds)
    for a in actions:
        assert f"{a.kind}(" in a.code or a.code.startswith("await checkItemInsideChest("), a


def test_checks_keep_actions_executable():
    empty = {"voxels": [], "inventory": {}, "status": {"position": {"x": 0, "y": 4, "z": 0}, "entities": {}}}
    kinds = {a.kind for a in (RandomActions(1, DD, ()).next(empty) for _ in range(300))}
    # nothing to mine, place, give, attack, smelt, plant or open: none of those is tried
    assert not kinds & {
        "mineBlock",
        "placeItem",
        "giveToPlayer",
        "killMob",
        "smeltItem",
        "plantWheatSeeds",
        "milkCow",
        "tillLand",
        "getItemFromChest",
        "destroyCrop",
        "bot.equip",
        "sendSignal",
    }
    gen = RandomActions(2, DD, ("Raze",))
    for _ in range(300):
        a = gen.next(OBS[0])
        if a.kind == "giveToPlayer":
            assert '"Raze"' in a.code and any(f'"{i}"' in a.code for i in OBS[0]["inventory"])
        if a.kind == "smeltItem":
            assert '"potato"' in a.code
        if a.kind == "killMob":
            assert '"cow"' in a.code or '"chicken"' in a.code


def test_smelts_only_what_the_server_can_smelt():
    # clay_ball and wet_sponge were once in the Random baseline's own list; the server's furnace cannot smelt them
    unsmeltable = {**OBS[1], "inventory": {"clay_ball": 4, "wet_sponge": 1, "coal": 3}}
    gen = RandomActions(3, DD, ())
    assert "smeltItem" not in {gen.next(unsmeltable).kind for _ in range(300)}
    with_potato = {**unsmeltable, "inventory": {**unsmeltable["inventory"], "potato": 2}}
    smelts = [a.code for a in (gen.next(with_potato) for _ in range(300)) if a.kind == "smeltItem"]
    assert smelts and all('"potato"' in code for code in smelts)


async def test_random_plays_whole_episodes_in_both_scenarios(tmp_path):
    recs = await asyncio.gather(
        play_series("mushroom_war", "random", "random", tmp_path / "mw", length=20, clock="lockstep"),
        play_series("dash_and_dine", "random", "do_nothing", tmp_path / "dd", length=20, clock="lockstep"),
    )
    for (rec,), key in zip(recs, ("mw", "dd")):
        assert rec.status == "ok", rec.error
        assert all(n >= 1 for n in rec.iterations["red"]), rec.iterations
        out = tmp_path / key / "episode_000"
        assert not list(out.glob("play-*.error.txt"))
        sides = ["red", "blue"] if key == "mw" else ["red"]
        for side in sides:
            data = json.loads((out / side / "random.json").read_text())
            sc = make_scenario(rec.scenario)
            # the same seed and the same observations give the same actions
            for name, actions in data["actions"].items():
                assert actions, name
                gen = RandomActions(data["seeds"][name], sc.primitives, data["recipients"][name])
                assert [gen.next(a["saw"]).code for a in actions] == [a["code"] for a in actions]
            # what each player did is in its event log
            for name in data["actions"]:
                assert (out / "events" / f"{name}.jsonl").stat().st_size > 0
    mw = json.loads((tmp_path / "mw" / "episode_000" / "red" / "random.json").read_text())
    assert mw["seeds"] == {"Ryn": "1000/red/0", "Raze": "1000/red/1"}
    assert mw["recipients"]["Ryn"] == ["Raze"]
    dd = json.loads((tmp_path / "dd" / "episode_000" / "red" / "random.json").read_text())
    assert dd["recipients"]["Raze"] == ["Ryn", "Red_Server"]
