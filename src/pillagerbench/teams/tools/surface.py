"""The game as tools: one declared tool surface per scenario and side, built from what is declared once
elsewhere: the primitives' modules (`js/bot/primitives/modules.json`) and their documentation (each
`<module>.md`: a function's signature and the comment lines above it), the observation, the scenario's
description. Every front (MCP, Inspect, the `tools` team) reads the same `ToolSpec`s.

For each player of the team: `observe`, `run_code`, one tool per documented primitive with typed
arguments (`mineBlock(player, name, count, point, maxDistance)`), `wait`, `chat`; for the team: `status`.
A primitive's call is played as the one line of agent code it stands for (`call_code`), so it runs in
the same sandbox, under the same fair-play checks, as any program.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from typing import Any

from pillagerbench.players import primitives as prim
from pillagerbench.scenarios import Scenario
from pillagerbench.teams.tools.spec import ToolSpec

POSITION: dict[str, Any] = {
    "type": "array",
    "items": {"type": "number"},
    "minItems": 3,
    "maxItems": 3,
    "description": "[x, y, z]",
}
ITEMS: dict[str, Any] = {
    "type": "object",
    "additionalProperties": {"type": "integer", "minimum": 1},
    "description": "item name -> count",
}
# a primitive's parameter -> its JSON schema, by the name the documentation gives it; None: not offered
# as a tool argument (a JavaScript callback), left undefined
PARAMETERS: dict[str, dict[str, Any] | None] = {
    "name": {"type": "string"},
    "itemName": {"type": "string"},
    "fuelName": {"type": "string"},
    "mobName": {"type": "string"},
    "playerName": {"type": "string"},
    "username": {"type": "string"},
    "crop": {"type": "string"},
    "count": {"type": "integer"},
    "groundY": {"type": "integer"},
    "maxDistance": {"type": "number", "minimum": 0},
    "distance": {"type": "number", "minimum": 0},
    "maxTime": {"type": "number", "minimum": 0},
    "timeout": {"type": "number", "minimum": 0},
    "timeoutDuration": {"type": "number", "minimum": 0},
    "point": {**POSITION, "type": ["array", "null"]},
    "position": POSITION,
    "chestPosition": POSITION,
    "direction": POSITION,
    "itemsToGet": ITEMS,
    "itemsToDeposit": ITEMS,
    "lands": {"type": "array", "items": {"type": "string"}},
    "task": {"type": ["string", "null"]},
    "callback": None,
}
VECTORS = {
    name for name, schema in PARAMETERS.items() if schema is not None and schema.get("items") == POSITION["items"]
}
MAX_TICKS = 20 * 120  # run_code's max_ticks at most: an episode's length of game time (20 ticks a second)
MAX_CHAT = 256
_SIGNATURE = re.compile(r"^(?:async )?function (\w+)\(([^)]*)\)\s*\{\s*\.\.\.\s*\}\s*(?://\s*(.*))?$")


@dataclass(frozen=True)
class Primitive:
    """One documented primitive: its name, parameters (after `bot`) with their defaults, documentation."""

    name: str
    parameters: tuple[tuple[str, str | None], ...]  # (name, the default as written, or None)
    doc: str


def primitives_of(modules: list[str]) -> list[Primitive]:
    """The documented functions of these primitive modules, in their documentation's order."""
    out: list[Primitive] = []
    for module in modules:
        comments: list[str] = []
        for line in prim.doc(module).splitlines():
            found = _SIGNATURE.match(line.strip())
            if found is None:
                comments = [*comments, line.strip().removeprefix("//").strip()] if line.startswith("//") else []
                continue
            name, args, trailing = found.groups()
            params = tuple(_parameter(a) for a in args.split(",")[1:])  # the first is `bot`
            out.append(Primitive(name, params, " ".join([*comments, trailing or ""]).strip()))
            comments = []
    return out


def _parameter(text: str) -> tuple[str, str | None]:
    name, _, default = text.partition("=")
    return name.strip(), (default.strip() or None)


def _default(written: str) -> Any:
    try:
        return json.loads(written)
    except ValueError:
        return None


def _player(players: list[str]) -> dict[str, Any]:
    return {"type": "string", "enum": list(players), "description": "which player of the team acts"}


def _object(properties: dict[str, Any], required: list[str]) -> dict[str, Any]:
    return {"type": "object", "properties": properties, "required": required, "additionalProperties": False}


def primitive_tool(p: Primitive, players: list[str]) -> ToolSpec:
    properties: dict[str, Any] = {"player": _player(players)}
    required = ["player"]
    for name, default in p.parameters:
        schema = PARAMETERS.get(name, {})
        if schema is None:
            continue
        properties[name] = dict(schema) if default is None else {**schema, "default": _default(default)}
        if default is None:
            required.append(name)
    return ToolSpec(p.name, p.doc, _object(properties, required), acting=True)


def tools_of(scenario: Scenario, side: str) -> list[ToolSpec]:
    """The declared tool surface of `side`'s team in `scenario`."""
    players = scenario.side(side).player_names
    modules = list(scenario.primitives)
    player = _player(players)
    code_doc = (
        "Run a JavaScript program on the player's bot, in the same sandbox as any team's code: the body of an "
        "async function of `bot`, with these functions in scope:\n\n" + prim.docs([*modules, "mineflayer"])
    )
    ticks = {"type": "integer", "minimum": 1, "maximum": MAX_TICKS}
    core = [
        ToolSpec(
            "status",
            'The team\'s game: {"phase": "pre_game" | "play" | "over", "episode": N, "players": [...], '
            '"time_left_s": T, "scores": {"red": R, "blue": B}}. Acting calls wait for the game.',
            _object({}, []),
        ),
        ToolSpec(
            "observe",
            "What the player sees and holds now: position, health, inventory, nearby blocks, chests, entities.",
            _object({"player": player}, ["player"]),
        ),
        ToolSpec(
            "run_code",
            code_doc + "\n\nReturns the run's events when the program ends, after `max_ticks` ticks of game "
            "time (20 a second), or at the whistle.",
            _object({"player": player, "code": {"type": "string"}, "max_ticks": ticks}, ["player", "code"]),
            acting=True,
        ),
        ToolSpec(
            "wait",
            "The player does nothing for `ticks` ticks of game time (20 a second), or to the whistle.",
            _object({"player": player, "ticks": ticks}, ["player", "ticks"]),
            acting=True,
        ),
        ToolSpec(
            "chat",
            "The player says `text` in the game's chat (everyone, the opponents too, reads it).",
            _object({"player": player, "text": {"type": "string", "maxLength": MAX_CHAT}}, ["player", "text"]),
            acting=True,
        ),
    ]
    return core + [primitive_tool(p, players) for p in primitives_of(modules)]


def _js(name: str, value: Any) -> str:
    if name in VECTORS and isinstance(value, list):
        return "new Vec3(" + ", ".join(json.dumps(v) for v in value) + ")"
    return json.dumps(value)


RETURNED = "pillagerbench:returned "  # an onSave event's prefix that carries a primitive's return value


def call_code(p: Primitive, arguments: dict[str, Any]) -> str:
    """The one line of agent code a primitive's tool call stands for (arguments already checked), which
    hands its return value back as an onSave event (`RETURNED`)."""
    given = [name for name, _ in p.parameters if name in arguments]
    last = max((i for i, (name, _) in enumerate(p.parameters) if name in given), default=-1)
    args = ["bot"] + [
        _js(name, arguments[name]) if name in arguments else "undefined" for name, _ in p.parameters[: last + 1]
    ]
    return (
        f"const returned = await {p.name}({', '.join(args)})\n"
        f"if (returned !== undefined) save({json.dumps(RETURNED)} + JSON.stringify(returned))"
    )


def briefing(scenario: Scenario, side: str) -> str:
    """What an agent is told of the game before it plays: the scenario's description and its team."""
    own = scenario.side(side)
    return (
        f"{scenario.description()}\n\nYou are the {own.team_name} ({side}): your players are "
        f"{', '.join(own.player_names)}; the opponents are the {scenario.opponent(side).team_name}. "
        "Act through the tools: each acting tool (run_code, wait, chat and the primitives) is an action of one "
        "of your players; `status` tells the phase, the time left and the scores."
    )
