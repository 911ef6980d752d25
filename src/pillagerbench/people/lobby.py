"""What the lobby shows of the game (docs/people.md): the scenario's briefing and the map of the layout
played, the same self-contained page `pillagerbench layout show` writes (replay/map_page.py draws it as
the replay page draws a recording: js/replay/map.js, inline; the page loads nothing)."""

from __future__ import annotations

from typing import Any

from pillagerbench.replay.map_page import render_still, still_data
from pillagerbench.scenarios import Scenario
from pillagerbench.scenarios.arena import GROUND_Y, Arena


def notes(scenario: Scenario, arena: Arena) -> list[str]:
    """What the map cannot show: where it lies, the spawns, the chests' and furnaces' contents, the mobs."""
    (x0, _, z0), (x1, _, z1) = arena.box
    out = [f"top-down, north (-z) up, east (+x) right: x {x0}..{x1}, z {z0}..{z1}; players stand at y = {GROUND_Y + 1}"]
    out += [
        f"{side.key}: " + ", ".join(f"{p.name} at {p.spawn}" for p in side.players) + f"; centre {side.center}"
        for side in scenario.sides
    ]
    out += [f"{p.name} at {p.spawn}" for p in scenario.extra_players]
    out += [f"chest at {pos}: {_listed(items) or 'empty'}" for pos, items in arena.chests.items()]
    out += [f"furnace at {pos}: {_listed(contents)}" for pos, contents in arena.furnaces.items()]
    out += [f"egg farm: the chickens lay into the chest at {chest}" for chest, _ in arena.egg_farms]
    mobs: dict[str, int] = {}
    for name, _ in arena.mobs:
        mobs[name] = mobs.get(name, 0) + 1
    return out + [f"{count} {name}" for name, count in mobs.items()]


def _listed(contents: dict) -> str:
    """{"bowl": 64} -> "bowl 64"; {"fuel": ["coal", 64]} -> "fuel coal 64"."""
    return ", ".join(" ".join(map(str, [k, *(v if isinstance(v, list) else [v])])) for k, v in contents.items())


def layout_page(scenario: Scenario, play: bool = True) -> str:
    """The map of `scenario`'s layout: one HTML page, top-down, the arena as built (blocks, mobs, every player
    at its spawn) and, in words, what the picture cannot show; `play`: the line saying how to play it."""
    arena = scenario.arena
    data = still_data(
        arena.box,
        arena.blocks,
        arena.mobs,
        [(p.name, p.spawn) for p in scenario.all_players()],
        {side.key: side.player_names for side in scenario.sides},
    )
    key = scenario.layout_key
    title = f"{scenario.title}, layout {key} ({scenario.split})"
    lines = notes(scenario, arena)
    if play:
        lines.append(f"play it: pillagerbench run scenario={scenario.key} layout={key}")
    return render_still(data, title, lines)


def briefing_of(scenario: Scenario, split: str | None = None) -> dict[str, Any]:
    """What every page is told before the game: the scenario, its description, the sides' players (a
    person signals a teammate by name) and, when each episode is played on a layout of its own (`split=`
    dev or test), that the map shown is the episode's once it starts."""
    out: dict[str, Any] = {
        "title": scenario.title,
        "scenario": scenario.key,
        "description": scenario.description(),
        "sides": {side.key: list(side.player_names) for side in scenario.sides},
        "layout": None,
        "map": None,
    }
    if split not in (None, "paper"):
        out["map_note"] = (
            f"split={split}: each episode is played on a layout of its own; its map is shown once it starts"
        )
    return out
