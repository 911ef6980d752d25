"""The game's tools as Inspect tools (`-T team=agent`): one per `ToolSpec` of the sample's seat
(teams/tools/), with its name, documentation and JSON schema as declared, each call answered by
`Seat.call`; a refusal (`ToolResult.error`) raises `ToolError`, which the model reads as the call's
error. The seat is the sample's own, found through the sample's store (`SEAT`, set by seated.py).

An agent takes them as `react(tools=pillagerbench_tools())`: a tool source resolved inside the sample,
so one agent plays any scenario and side (each has its own players and primitives).
"""

from __future__ import annotations

from typing import Any
from weakref import WeakKeyDictionary

from inspect_ai.tool import Tool, ToolDef, ToolError, ToolParams, ToolSource
from inspect_ai.util import store

from pillagerbench.teams.tools import SEATS, Seat, ToolSpec

SEAT = "pillagerbench_seat"  # the sample's store: its seat's key (teams.tools.SEATS)

_TOOLS: WeakKeyDictionary[Seat, list[Tool]] = WeakKeyDictionary()


class NoSeat(RuntimeError):
    """The tools were called outside a sample of `-T team=agent`."""


def current_seat() -> Seat:
    """The seat of the sample running now."""
    key = store().get(SEAT)
    seat = SEATS.get(key) if isinstance(key, str) else None
    if seat is None:
        raise NoSeat("no PillagerBench seat in this sample: the game's tools play with -T team=agent (docs/inspect.md)")
    return seat


def game_over() -> bool:
    """The sample's run is over (its series ended): an agent's loop may stop."""
    return current_seat().phase == "over"


def inspect_tool(seat: Seat, spec: ToolSpec) -> Tool:
    """One declared tool as an Inspect tool answering from `seat`."""

    async def execute(**arguments: Any) -> str:
        result = await seat.call(spec.name, arguments)
        if result.error:
            raise ToolError(result.text)
        return result.text

    parameters = ToolParams.model_validate(spec.parameters)
    for name, schema in parameters.properties.items():
        schema.description = schema.description or name  # Inspect wants every parameter described
    # parallel: one model turn's calls (one per player) run at once; on the lockstep clock they start on one tick
    return ToolDef(
        execute, name=spec.name, description=spec.description, parameters=parameters, parallel=True
    ).as_tool()


def seat_tools(seat: Seat) -> list[Tool]:
    """Every tool of `seat`, as Inspect tools (made once per seat)."""
    if seat not in _TOOLS:
        _TOOLS[seat] = [inspect_tool(seat, spec) for spec in seat.tools]
    return _TOOLS[seat]


class SeatTools(ToolSource):
    """The tools of whatever sample asks: Inspect resolves a tool source at each model call."""

    async def tools(self) -> list[Tool]:
        return seat_tools(current_seat())


def pillagerbench_tools() -> list[Tool | ToolDef | ToolSource]:
    """The game's tools for an agent: `react(tools=pillagerbench_tools())`."""
    return [SeatTools()]
