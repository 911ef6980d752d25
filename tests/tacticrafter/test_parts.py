"""TactiCrafter's parts without a game server: tactics tags, the causal graph, event
deduplication and digests, memory files."""

from __future__ import annotations

import json

import pytest

from pillagerbench.scenarios import make_scenario
from pillagerbench.teams.tacticrafter.causal import CausalGraph, Relation, parse_relations
from pillagerbench.teams.tacticrafter.events import dedupe, digest, opponent_chat, own_chat_with_inventory
from pillagerbench.teams.tacticrafter.memory import Memory
from pillagerbench.teams.tacticrafter.tactics import extract_tactics

from .conftest import GRAPH


def chat(line: str, **inv) -> list:
    return ["onChat", {"onChat": line, "inventory": inv, "voxels": ["grass_block"], "status": {}}]


def observe(**inv) -> list:
    return ["observe", {"inventory": inv, "voxels": ["slime_block"], "status": {"position": {"x": 1, "y": 4, "z": 2}}}]


# --- tactics tags ----------------------------------------------------------------------------------


def test_tactics_between_tags_numbered_at_most_six():
    text = (
        "Reasoning... [tactics] is the format.\n[tactics]\n1. Ryn mines slime.\n2. Raze harvests\n"
        "   red mushrooms when they regrow.\n" + "".join(f"{k}. Item {k}.\n" for k in range(3, 9)) + "[tactics end]"
    )
    got = extract_tactics(text)
    lines = got.splitlines()
    assert len(lines) == 6 and lines[0] == "1. Ryn mines slime."
    assert lines[1] == "2. Raze harvests red mushrooms when they regrow."
    assert extract_tactics("[TACTICS]\n1) Ryn waits.\n[Tactics End]") == "1) Ryn waits."


def test_tactics_problems_are_reasons():
    with pytest.raises(ValueError, match="no \\[tactics\\]"):
        extract_tactics("1. Ryn mines slime.")
    with pytest.raises(ValueError, match="empty"):
        extract_tactics("[tactics]\n\n[tactics end]")
    # an answer cut before the end tag still counts when its items are there
    assert extract_tactics("[tactics]\n1. Ryn mines slime.\n2. Raze") == "1. Ryn mines slime.\n2. Raze"
    with pytest.raises(ValueError, match="no \\[tactics end\\]"):
        extract_tactics("[tactics]\nRyn mines")


# --- causal graph ----------------------------------------------------------------------------------


def test_causal_graph_shapes_render_and_parse_back():
    lists = parse_relations(GRAPH)
    objects = parse_relations({"relations": [{"action": a, "causes": c, "effects": e} for a, c, e in GRAPH]})
    mapping = parse_relations({a: [c, e] for a, c, e in GRAPH})
    assert lists == objects == mapping and len(lists) == len(GRAPH)
    graph = CausalGraph(lists)
    text = graph.render()
    assert "Action: mineBlock(bot, 'slime_block', 3); Cause: []; Effect ['slime_block']" in text
    assert CausalGraph.parse_text(text).relations == graph.relations
    assert CausalGraph.from_json(graph.to_json()).relations == graph.relations
    assert graph.missing_modules(["mineBlock", "placeItem", "multiAgent", "killMob", "giveToPlayer"]) == []
    assert graph.missing_modules(["mineBlock", "craftItem"]) == ["craftItem"]


@pytest.mark.parametrize(
    "bad,why",
    [
        ("not json", "relations"),
        ([["a", "b"]], "relation 1"),
        ([["", [], []]], "action"),
        ([["f()", [1, [2]], []]], "causes"),
        ({"f()": ["x"]}, "causes"),
        (42, "JSON list"),
    ],
)
def test_invalid_graphs_say_why(bad, why):
    with pytest.raises(ValueError, match=why):
        parse_relations(bad)


def test_merge_adds_new_and_replaces_same_action():
    graph = CausalGraph(parse_relations(GRAPH))
    n = len(graph)
    stats = graph.merge(
        [
            Relation("mineBlock(bot, 'slime_block', 3)", (), ("slime_block", "dirt")),
            Relation("craftItem(bot, 'bread', 1)", ("wheat",), ("bread",)),
            Relation("sendSignal(bot, 'Raze')", (), ()),
        ]
    )
    assert stats == {"added": 1, "changed": 1, "total": n + 1}
    assert graph.relations[0].effects == ("slime_block", "dirt") and graph.relations[-1].action.startswith("craftItem")


# --- deduplication ---------------------------------------------------------------------------------


def test_dedup_removes_repeated_chat_sequences_of_agents_only():
    loop = [chat("<Ryn> Mined 1 slime_block"), chat("<Ryn> No red_mushroom_block nearby, please explore first")]
    events = (
        loop * 5
        + [chat("Team red is clean!")] * 3
        + [["onError", {"onError": "boom"}]]
        + [chat("<Byte> Placed slime_block")] * 4
        + [chat("<Ryn> Done")]
        + [observe(slime_block=5)]
    )
    out, stats = dedupe(events, ["Ryn", "Raze", "Byte", "Blink"])
    lines = [e[1]["onChat"] for e in out if e[0] == "onChat"]
    assert lines == [
        "<Ryn> Mined 1 slime_block",
        "<Ryn> No red_mushroom_block nearby, please explore first",
        "Team red is clean!",
        "Team red is clean!",
        "Team red is clean!",
        "<Byte> Placed slime_block",
        "<Ryn> Done",
    ]
    assert out[-1][0] == "observe" and any(e[0] == "onError" for e in out)
    assert stats.before == len(events) and stats.after == len(out)
    assert stats.chat_before == 18 and stats.chat_after == 7
    assert stats.reduction == round(1 - len(out) / len(events), 4) > 0.4


def test_dedup_keeps_sequences_that_do_not_repeat_back_to_back():
    events = [chat("<Ryn> a"), chat("<Ryn> b"), chat("<Ryn> a"), chat("<Ryn> c"), chat("<Ryn> a"), chat("<Ryn> b")]
    out, stats = dedupe(events, ["Ryn"])
    assert out == events and stats.reduction == 0.0
    # interleaved speakers: each speaker's own sequence is compressed
    mixed = [chat("<Ryn> x"), chat("<Raze> y"), chat("<Ryn> x"), chat("<Raze> y"), chat("<Ryn> x")]
    out, _ = dedupe(mixed, ["Ryn", "Raze"])
    assert [e[1]["onChat"] for e in out] == ["<Ryn> x", "<Raze> y"]


def test_digests_feed_the_causal_and_opponent_prompts():
    sc = make_scenario("dash_and_dine")
    ryn = [
        chat("<Ryn> Harvested 4 wheat", wheat=4),
        chat("<Byte> Harvested 3 potato"),
        chat("Locked-in baked_potato as a submission item for team_blue"),
        chat("Scored 6 points for team_red"),
        chat("Team 1 is clean!"),  # the game masters name sides as upstream's: team_blue, Team 1
        chat("Team 0 is too dirty!"),
        chat("<Blue_Server> thanks"),
        chat("<Raze> Milked cow"),
        observe(wheat=4),
    ]
    raze = [chat("<Raze> Milked cow", milk_bucket=1), observe(milk_bucket=1)]
    digests = {"Ryn": digest(ryn), "Raze": digest(raze)}
    assert digests["Ryn"][0] == ["onChat", {"inventory": {"wheat": 4}, "onChat": "<Ryn> Harvested 4 wheat"}]
    assert digests["Ryn"][-1][1]["voxels"] == ["slime_block"]  # the last observe is kept whole
    evidence = own_chat_with_inventory(digests)
    assert "Ryn:\nChat: Harvested 4 wheat; Inventory: {'wheat': 4}" in evidence
    assert "Raze:\nChat: Milked cow; Inventory: {'milk_bucket': 1}" in evidence
    opp = opponent_chat(digests, sc, sc.side("blue"))
    assert opp.splitlines() == [
        "<Byte> Harvested 3 potato",
        "Locked-in baked_potato as a submission item for team_blue",
        "Team 1 is clean!",
        "<Blue_Server> thanks",
    ]


# --- memory ----------------------------------------------------------------------------------------


def test_memory_files_round_trip(tmp_path):
    mem = Memory(
        tactics="1. Ryn mines.",
        previous_tactics="1. Ryn waits.",
        tactics_source="updated",
        opponent_tactics="1. Byte mines.",
        opponent_source="inferred",
        graph=CausalGraph(parse_relations(GRAPH)),
        code={"Ryn": {"code": "async function m(bot) {}", "critique": "ok", "success": True, "error": None}},
        events={"Ryn": digest([chat("<Ryn> hi"), observe()])},
        episodes=3,
    )
    mem.write(tmp_path / "ep", episode=2, iterations={"Ryn": 4})
    code = json.loads((tmp_path / "ep" / "code.json").read_text())
    assert code["Ryn"]["iterations"] == 4 and code["Ryn"]["events"][0][1]["onChat"] == "<Ryn> hi"
    back = Memory.read(tmp_path / "ep")
    assert back.tactics == mem.tactics and back.previous_tactics == mem.previous_tactics
    assert back.opponent_tactics == mem.opponent_tactics and back.graph.relations == mem.graph.relations
    assert back.code == mem.code and back.events == mem.events
    # the causal graph also loads from its rendered text (upstream's format)
    (tmp_path / "txt").mkdir()
    (tmp_path / "txt" / "causal_graph.json").write_text(json.dumps(mem.graph.render()))
    assert Memory.read(tmp_path / "txt").graph.relations == mem.graph.relations
    assert Memory.from_dict(json.loads(json.dumps(mem.to_dict()))).to_dict() == mem.to_dict()
    with pytest.raises(FileNotFoundError):
        Memory.read(tmp_path / "nothing")


def test_a_cut_off_graph_keeps_its_complete_relations():
    from pillagerbench.teams.tacticrafter.causal import _parse_answer, _Text, complete_items

    cut = 'Here:\n```json\n[\n  ["mineBlock(bot, \'slime_block\', 3)", [], ["slime_block"]],\n  ["sendSignal(bot, \'Raze\')", [], []],\n  ["placeItem(bot, \'slime'
    assert complete_items(cut) == [
        ["mineBlock(bot, 'slime_block', 3)", [], ["slime_block"]],
        ["sendSignal(bot, 'Raze')", [], []],
    ]
    assert [r.action for r in _parse_answer(_Text(cut, truncated=True))] == [
        "mineBlock(bot, 'slime_block', 3)",
        "sendSignal(bot, 'Raze')",
    ]
    with pytest.raises(ValueError, match="relation 1 is neither"):
        _parse_answer(_Text(cut, truncated=False))  # only an answer the token limit cut is salvaged
    assert complete_items("no list") == [] and complete_items("[") == []


def test_code_answers_checked_with_acorn_and_an_empty_main_is_refused():
    from pillagerbench.teams.tacticrafter.base_agent import parse_code

    from .conftest import LOOP, code_answer

    sc = make_scenario("mushroom_war")
    assert parse_code(code_answer(LOOP), sc.primitives).entry == "keepFarming"
    template = "```javascript\n// helper functions first, then the main function last\nasync function main(bot) {\n  // ...\n}\n```"
    with pytest.raises(ValueError, match="does nothing"):
        parse_code(template, sc.primitives)
    with pytest.raises(ValueError, match="no ```javascript"):
        parse_code("Plan: mine.", sc.primitives)
    with pytest.raises(ValueError, match="does not parse"):
        parse_code("```js\nasync function main(bot) { await mineBlock(bot, 'x', 1\n}\n```", sc.primitives)


def test_opponent_chat_falls_back_to_the_worlds_chat_log_when_our_players_heard_less():
    from pillagerbench.scenarios import make_scenario
    from pillagerbench.teams.tacticrafter.events import opponent_chat

    sc = make_scenario("mushroom_war")
    blue = sc.side("blue")
    world = ["<Byte> Harvesting brown_mushroom_block in the blue_team area", "<Ryn> hello", "Team blue is clean!"]
    text = opponent_chat({"Ryn": [], "Raze": []}, sc, blue, world_chat=world)
    assert "<Byte> Harvesting" in text and "Team blue is clean!" in text and "<Ryn>" not in text
