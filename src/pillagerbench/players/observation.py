"""An observation: what a bot sees and holds, as js/bot/observe.js writes it (`Observer.observe()`),
typed as js/bot/bot_protocol.json declares it (`observation`, `status`; tests/players/test_bot_protocol.py
holds these TypedDicts to the declaration, and tests/players/test_player.py what the bot writes).

It is the answer to the `observe` request and the state part of every event (`[type, data]`: an
on* event's data adds its own key, e.g. `onChat`, to it). Every key may be missing: an observation
read back from a team's memory keeps only the inventory (teams/tacticrafter/events.py `digest`),
and a bot whose restart failed reports `{}`.
"""

from __future__ import annotations

from typing import TypedDict, cast


class Position(TypedDict):
    x: float
    y: float
    z: float


class Status(TypedDict, total=False):
    """The player's own state (observe.js `status()`)."""

    health: float
    food: float
    saturation: float
    oxygen: float
    position: Position
    velocity: Position
    yaw: float
    pitch: float
    onGround: bool
    equipment: list[str | None]  # head, chest, legs, feet, main hand, off hand
    name: str
    timeSinceOnGround: int
    isInWater: bool
    isInLava: bool
    isInWeb: bool
    isCollidedHorizontally: bool
    isCollidedVertically: bool
    biome: str
    entities: dict[str, float]  # mob name -> distance of the nearest, within 32 blocks
    timeOfDay: str
    inventoryUsed: int  # of the 36 main inventory slots
    elapsedTime: int  # ticks since the run started


class Observation(TypedDict, total=False):
    voxels: list[str]  # block names around the player
    status: Status
    inventory: dict[str, int]
    nearbyChests: dict[str, dict[str, int] | str]  # "x,y,z" -> contents, or "Unknown"
    blockRecords: list[str]  # every block name seen this run and not held


def observation(data: object) -> Observation:
    """An observation as the bot sent it (the JSON of the wire or of an events file, read as it is)."""
    return cast(Observation, data) if isinstance(data, dict) else {}


def is_whole(data: Observation) -> bool:
    """Whether it is a whole observation, not one a digest shortened to the inventory (or a failed
    restart's empty one): it has the player's status or the blocks around it."""
    return "status" in data or "voxels" in data
