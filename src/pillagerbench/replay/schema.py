"""The replay recording's records as pydantic models: the format's schema (docs/replays.md and
docs/replays.schema.json are generated from it, and tests check every recorded line against it).

A recording is gzip JSON lines: one `Header`, then the arena's `Blocks`, then timed records in the
order they happened, ending with `End` (missing when the run was killed). `t` is seconds since the
game started (wall clock). Unknown keys are allowed, so a newer recorder's extras don't break readers.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter

Pos = tuple[float, float, float]


class Record(BaseModel):
    model_config = ConfigDict(extra="allow")


class SideInfo(Record):
    team: str
    color: str
    players: list[str]


class Header(Record):
    """The first line: what was played."""

    type: Literal["header"]
    format: Literal["pillagerbench-replay"]
    version: int = Field(description="format version (1)")
    frame_hz: float = Field(description="frames per second")
    scenario: str
    title: str | None = None
    episode: int | None = None
    length: float | None = Field(None, description="episode length in seconds")
    seed: int | None = None
    sides: dict[str, SideInfo] = Field(description="side key (red, blue) -> team, colour, players")
    extra_players: list[str] = []
    started: float = Field(description="Unix time the recording started")


class Blocks(Record):
    """The arena at the start: every non-air block from the grass layer up, inside the arena's box."""

    type: Literal["blocks"]
    box: tuple[tuple[int, int, int], tuple[int, int, int]] = Field(description="[[x0, y0, z0], [x1, y1, z1]]")
    palette: list[str] = Field(description="block names; blocks refer to them by index")
    blocks: list[tuple[int, int, int, int]] = Field(description="[x, y, z, palette index]")


class Frame(Record):
    """Every player at one moment (FRAME_HZ a second)."""

    type: Literal["frame"]
    t: float
    tick: int = Field(description="the server's tick counter")
    players: list[tuple[str, float, float, float, int, int, str | None]] = Field(
        description="[name, x, y, z, yaw°, pitch°, held item or null]; yaw 0 faces +z, 90 faces -x"
    )


class BlocksChanged(Record):
    type: Literal["blocks_changed"]
    t: float
    blocks: list[tuple[int, int, int, str]] = Field(description="[x, y, z, new block name ('air' when removed)]")


class Item(Record):
    """An item entity appeared in the world (or its count changed)."""

    type: Literal["item"]
    t: float
    id: int
    item: str
    count: int
    pos: Pos


class ItemGone(Record):
    type: Literal["item_gone"]
    t: float
    id: int
    by: str | None = Field(description="the player who picked it up; null when it despawned or was removed")


class Mob(Record):
    """A mob appeared, moved or its health changed."""

    type: Literal["mob"]
    t: float
    id: int
    name: str
    pos: Pos
    health: float | None = None


class MobGone(Record):
    type: Literal["mob_gone"]
    t: float
    id: int


class Event(Record):
    """An event the server pushed on the control channel (chat, block_dug, item_picked_up, refused, …)."""

    type: Literal["event"]
    t: float
    event: dict[str, Any]


class Score(Record):
    """The game master's scores at game second t (the episode's timeline)."""

    type: Literal["score"]
    t: float
    scores: dict[str, float]


class Program(Record):
    """A player's program: the n-th `start` of this episode, an `error` it raised, its `end`."""

    type: Literal["program"]
    t: float
    player: str
    what: Literal["start", "error", "end"]
    run: int
    message: str | None = None


class End(Record):
    """The last line; missing when the run was killed during the game."""

    type: Literal["end"]
    t: float
    frames: int
    scores: dict[str, float] | None = None
    error: str | None = Field(None, description="why the recording stopped early (the server died)")


AnyRecord = Annotated[
    Header | Blocks | Frame | BlocksChanged | Item | ItemGone | Mob | MobGone | Event | Score | Program | End,
    Field(discriminator="type"),
]
RECORD = TypeAdapter(AnyRecord)


def json_schema() -> dict:
    """The JSON Schema of one line of a recording (docs/replays.schema.json)."""
    schema = RECORD.json_schema()
    schema["title"] = "One line of a PillagerBench replay recording (replay.jsonl.gz)"
    return schema
