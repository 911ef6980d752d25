from __future__ import annotations

import json

from pillagerbench.agents import context as C


def chat(who, msg):
    return ["onChat", {"onChat": f"<{who}> {msg}" if who else msg}]


OBS = {
    "voxels": ["slime_block", "grass_block", "red_mushroom_block"],
    "inventory": {"red_mushroom": 2, "bread": 1},
    "status": {
        "position": {"x": -7.5, "y": 4, "z": -9.5},
        "health": 20,
        "food": 18.5,
        "entities": {"cow": 7.25, "chicken": 3.0},
        "equipment": [None, None, None, None, "bread", None],
        "timeOfDay": "noon",
    },
    "nearbyChests": {"(-7, 4, -7)": {"bucket": 16}, "(-7, 4, 5)": "Unknown"},
}


def test_observation_texts():
    assert C.nearby_blocks(OBS) == "grass_block, red_mushroom_block, slime_block"
    assert C.nearby_entities(OBS) == "chicken (3 blocks away), cow (7.2 blocks away)"
    assert C.inventory_text(OBS) == "bread: 1, red_mushroom: 2"
    assert C.position_text(OBS) == "x=-7.5, y=4, z=-9.5"
    assert "Hunger: 18.5/20" in C.status_text(OBS) and "Equipment: bread" in C.status_text(OBS)
    assert C.chests_text(OBS) == "(-7, 4, -7): bucket: 16\n(-7, 4, 5): contents unknown"
    empty = {}
    assert (C.nearby_blocks(empty), C.nearby_entities(empty), C.inventory_text(empty)) == ("none", "none", "empty")
    assert C.last_observation([chat("A", "x"), ["observe", OBS]]) is OBS


def test_chat_compression_as_upstream():
    events = [
        chat("Ryn", "a"),
        chat("Ryn", "a"),
        chat("Ryn", "a"),
        chat(None, "Team red is clean!"),
        chat("Ryn", "b"),
        chat("Raze", "x"),
        chat("Ryn", "c"),
        chat("Ryn", "b"),
        chat("Ryn", "c"),
        ["onError", {"onError": "boom"}],
        chat(None, "Team red is clean!"),
        chat("Byte", "z"),
        chat("Byte", "z"),
    ]
    kept = C.chat_lines(events, ["Ryn", "Raze"])
    assert kept == [
        "<Ryn> a",
        "Team red is clean!",
        "<Ryn> b",
        "<Raze> x",
        "<Ryn> c",
        "Team red is clean!",
        "<Byte> z",
        "<Byte> z",
    ]
    assert C.chat_log_text([], ["Ryn"]) == "none"
    many = [chat("Server", str(i)) for i in range(10)]
    assert C.chat_log_text(many, max_lines=3).splitlines() == [
        "... (7 earlier lines left out)",
        "<Server> 7",
        "<Server> 8",
        "<Server> 9",
    ]


def test_errors_and_episode_events(tmp_path):
    events = [
        ["onError", {"onError": "Error: a"}],
        ["onError", {"onError": "Error: b"}],
        ["onError", {"onError": "Error: a"}],
        ["observe", OBS],
    ]
    (tmp_path / "Ryn.jsonl").write_text("\n".join(json.dumps(e) for e in events) + "\n{torn")
    got = C.episode_events({"events_dir": str(tmp_path)}, ["Ryn", "Raze"])
    assert got["Raze"] == [] and len(got["Ryn"]) == 4
    assert C.errors_text(got["Ryn"]) == "Error: a\nError: b"
    assert C.errors_text([]) == "none"
    assert C.episode_events({}, ["Ryn"]) == {"Ryn": []}
