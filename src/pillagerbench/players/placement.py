"""Where a player stands and what it holds, read and set through the arena's control channel:
the snapshot a restarted bot is given back, the teleport that waits until the bot has arrived, the
wait until a reset's inventory has reached the bot."""

from __future__ import annotations

import asyncio
from collections.abc import Awaitable, Callable, Sequence

from pillagerbench.server.seams import Control

from . import bot_protocol
from .channel import BotChannel, PlayerError
from .observation import Observation

Equipment = bot_protocol.Equipment | None


async def snapshot(server: Control | None, name: str, last_observation: Observation) -> dict | None:
    """Inventory and position to restore: from the server while the player is still connected,
    else from the last observation seen."""
    if server is None:
        return None
    try:
        players = await asyncio.wait_for(server.players(), 2)
        pos = next((p["pos"] for p in players if p["name"] == name), None)
        if pos is not None:
            inv = await asyncio.wait_for(server.inventory(name), 2)
            items: dict[str, int] = {}
            for slot in inv:
                items[slot["name"]] = items.get(slot["name"], 0) + slot["count"]
            return {"items": items, "pos": pos}
    except Exception:  # noqa: BLE001 - fall back to the last observation
        pass
    obs = last_observation
    if not obs:
        return None
    p = (obs.get("status") or {}).get("position")
    return {"items": dict(obs.get("inventory") or {}), "pos": [p["x"], p["y"], p["z"]] if p else None}


async def restore(server: Control | None, channel: BotChannel, name: str, saved: dict | None) -> None:
    """Give a restarted bot back what `snapshot` saved."""
    if not saved or server is None:
        return
    await server.set_inventory(name, saved["items"])
    if saved["pos"]:
        await teleport(server, channel, name, saved["pos"])


# (yaw, pitch) a player faces at login. On the lockstep clock each episode begins so: a player stopped at
# the whistle keeps turning for as long as its stop takes on the wall clock, and the next episode began
# facing wherever that left it (a series' later episodes parted run after run). The real clock keeps the
# look, as upstream's reset (a teleport) did.
LOGIN_LOOK = (0.0, 0.0)


async def teleport(server: Control, channel: BotChannel, name: str, pos: list[float], clock: str = "real") -> None:
    """Teleport, then wait until the bot has settled there (three tries). On the lockstep clock the
    player faces as at login (LOGIN_LOOK); on the real clock it keeps its own look."""
    yaw, pitch = LOGIN_LOOK if clock == "lockstep" else (None, None)
    for _attempt in range(3):
        await server.teleport(name, pos, yaw, pitch)
        settled = await channel.settle(pos, 3, wait=6)
        if settled is True:
            return
    raise PlayerError(f"{name}: teleport to {pos} did not arrive (bot at {settled})")


async def reset_to(server: Control, channel: BotChannel, name: str, position: Sequence[float], clock: str) -> None:
    """A reset's teleport: to the middle of a whole-number block (`centred`), facing as `teleport` says."""
    await teleport(server, channel, name, centred(position), clock)


async def wait_inventory(
    observe: Callable[[], Awaitable[Observation]], inventory: dict[str, int], equipment: Equipment
) -> None:
    """Wait (up to 100 observations) until the bot holds the inventory and equipment a reset gave it."""
    want = dict(inventory)
    for name in equipment_names(equipment):
        want.setdefault(name, 1)
    for _ in range(100):
        inv = (await observe())["inventory"]
        if all(inv.get(k, 0) >= v for k, v in want.items()):
            return
        await asyncio.sleep(0.02)


def reset_items(inventory: dict[str, int] | None, equipment: Equipment) -> dict[str, int]:
    """The items a reset sets: the inventory, plus one of each piece of equipment it does not list."""
    items = dict(inventory or {})
    for name in equipment_names(equipment):
        if name not in (inventory or {}):  # equipment not listed in the inventory is extra
            items[name] = items.get(name, 0) + 1
    return items


def centred(position: Sequence[float]) -> list[float]:
    """Whole-number x/z mean the middle of that block (as Minecraft's /tp does)."""
    x, y, z = (float(v) for v in position)
    return [x + 0.5 if x.is_integer() else x, y, z + 0.5 if z.is_integer() else z]


def equipment_names(equipment: Equipment) -> list[str]:
    if equipment is None:
        return []
    if isinstance(equipment, dict):
        return [v for v in equipment.values() if v]
    return [v for v in equipment if v]
