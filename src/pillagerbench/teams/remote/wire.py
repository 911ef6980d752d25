"""The remote-team protocol, version 1: JSON over HTTP between the benchmark (client) and a team
server in any language. The messages are pydantic models here; `schemas()` gives their JSON Schemas
(docs/remote-teams.md and `pillagerbench remote-schemas` write them out).

    GET  {url}/          -> Hello                       (preflight, before the run starts)
    POST {url}/pregame   PregameRequest  -> Programs    (one program per player)
    POST {url}/events    EventsRequest   -> Programs    (new programs for some players, or none)
    POST {url}/postgame  PostgameRequest -> Ack
"""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field

PROTOCOL = 1


class _Message(BaseModel):
    model_config = ConfigDict(extra="allow")


class Hello(_Message):
    """The team server's answer to GET {url}/."""

    protocol: int = Field(description="the protocol version the team speaks (1)")
    name: str = Field(default="remote", description="the team's name, for the record")


class PlayerInfo(BaseModel):
    name: str
    spawn: list[float] = Field(description="x, y, z where the player starts")


class SideInfo(BaseModel):
    key: str = Field(description="red or blue")
    team_name: str
    players: list[PlayerInfo]
    opponent_team_name: str
    opponent_players: list[str]


class ScenarioInfo(BaseModel):
    key: str
    title: str
    description: str = Field(description="the scenario's rules, as the LLM teams read them")


class PregameRequest(BaseModel):
    protocol: int = PROTOCOL
    episode: int
    episode_length_s: float
    scenario: ScenarioInfo
    side: SideInfo
    primitives: list[str] = Field(description="primitive functions the players' code may call")
    primitives_docs: str = Field(description="their documentation (markdown), as the LLM teams read it")
    observations: dict[str, Any] = Field(description="player name -> its observation after the reset")
    last_episode: dict[str, Any] | None = Field(
        description="the last episode's record, score timeline and chat log (null in episode 0)"
    )


class Programs(_Message):
    """Team -> benchmark: JavaScript programs by player name. A player not named keeps its program."""

    programs: dict[str, str] = Field(default_factory=dict)


class EventsRequest(BaseModel):
    protocol: int = PROTOCOL
    episode: int
    t: float = Field(description="seconds since the game started")
    time_left_s: float
    events: dict[str, list[Any]] = Field(
        description="player name -> its events since the last message "
        "(the same events LLM teams read: chat, errors, observe ...)"
    )


class PostgameRequest(BaseModel):
    protocol: int = PROTOCOL
    episode: int
    record: dict[str, Any] = Field(description="the episode record (scores, winner, iterations, problems)")
    chat: list[str] = Field(description="the episode's chat log")


class Ack(_Message):
    pass


MESSAGES: dict[str, type[BaseModel]] = {
    "hello": Hello,
    "pregame_request": PregameRequest,
    "programs": Programs,
    "events_request": EventsRequest,
    "postgame_request": PostgameRequest,
    "ack": Ack,
}


def schemas() -> dict[str, dict]:
    """message name -> JSON Schema (draft 2020-12, as pydantic writes it)."""
    return {name: model.model_json_schema() for name, model in MESSAGES.items()}


def schema_section() -> str:
    """The Markdown section of docs/remote-teams.md that holds every message's JSON Schema."""
    import json

    parts = []
    for name, schema in schemas().items():
        parts.append(f"### `{name}`\n\n```json\n{json.dumps(schema, indent=1)}\n```\n")
    return "\n".join(parts)


if __name__ == "__main__":  # python -m pillagerbench.teams.remote.wire > section.md
    print(schema_section(), end="")
