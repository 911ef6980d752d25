"""What every front (MCP, Inspect, our `tools` team) reads of the game as tools: one `ToolSpec` per tool
(its name, its documentation, one JSON schema of its arguments) and one `ToolResult` per call."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any


@dataclass(frozen=True)
class ToolSpec:
    name: str
    description: str
    parameters: dict[str, Any]  # a JSON schema of type "object"
    acting: bool = False  # an action in the world: ends the pre-game and lets game time pass


@dataclass(frozen=True)
class ToolResult:
    text: str  # what the caller reads (JSON for status, the run's events for actions)
    error: bool = False  # a refusal: unknown tool, bad arguments, a player not on the team, ...
    data: dict[str, Any] = field(default_factory=dict)  # the same as a JSON value, for fronts that want it
