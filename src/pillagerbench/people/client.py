"""People playing from a real Minecraft Java 1.16.5 client (`humans.client=minecraft`, docs/people.md).

A person's player is then no bot: the person logs in under the player's own name (Ryn) at the gate's
address, the gate (`LoginGate`) admits the names people play here and nobody else, and the player is
the person's client on the same server, under the same checks (reach, dig time, placing, movement) as
any. What the match does to a player it does through the server's control channel (`ClientPlayer`: the
reset's inventory, game mode and place; the observation read from the server), so the records (the
world's events, the replay's frames, the scores) show the player as any. Joining is being ready
(`Clients.wait_joined`); a person who leaves is gone from the world (the episode goes on, the team's) and
one who comes back is put where the player was, holding what it held, a second before (`Clients.rejoined`).
The gate is people/gate.py.
"""

from __future__ import annotations

import asyncio
import math
import time
from collections.abc import Sequence

from pillagerbench.people.seats import Seats
from pillagerbench.players import Player, placement
from pillagerbench.players.observation import Observation
from pillagerbench.server.seams import Control

ARRIVE_S = 5.0  # a teleported client has this long to be seen there (it confirms the teleport)
JOIN_POLL_S = 0.25


class ClientPlayer(Player):
    """A player a person plays from a Minecraft client: no bot is launched; the match's reset and
    observations go through the server's control channel. A team gets a seat for it (people.SeatHandle):
    nothing runs code on it, so primitives and programs do not exist for it."""

    def __init__(self, name: str, server: Control, gamemode: str):
        super().__init__(name, 0, server=server)  # the bot process is never launched
        self.control, self.gamemode = server, gamemode
        self.last: Observation = {}  # the last observation read while the person was in the world
        self.away = False  # the person was not in the world at the last look (a reset's or a second's)

    async def launch(self) -> None:
        return None

    async def start(self) -> None:
        return None  # the person joins when they join (Clients.wait_joined)

    async def run(self, code: str, *, timeout: float | None = None, on_event=None) -> list:
        raise RuntimeError(f"{self.name} is played from a Minecraft client: no code runs on it")

    async def stop(self) -> None:
        return None  # a person's hands are their own

    async def close(self) -> None:
        return None

    async def lag(self, *, reset: bool = False) -> dict:
        return {}  # no bot: no physics ticks of ours to be late

    async def where(self) -> list[float] | None:
        """The player's position as the server has it, or None while the person is not in the world."""
        found = [p["pos"] for p in await self.control.players() if p["name"] == self.name]
        return list(found[0]) if found else None

    async def reset(
        self,
        *,
        position: Sequence[float] | None = None,
        inventory: dict[str, int] | None = None,
        equipment: placement.Equipment = None,
        seed: int | None = None,
    ) -> list:
        """The reset, through the server: the items, the game mode and the place (a person not in the world
        is put there when they come back: `Clients.rejoined`)."""
        self.away = await self.where() is None
        if not self.away:
            await self.put(placement.reset_items(inventory, equipment), position)
        pos = placement.centred(position) if position is not None else None
        self.last = {"inventory": dict(inventory or {})}
        if pos is not None:
            self.last["status"] = {"position": {"x": pos[0], "y": pos[1], "z": pos[2]}, "name": self.name}
        return await self.observe()

    async def put(self, items: dict[str, int], position: Sequence[float] | None) -> None:
        """The player holds `items`, plays in its game mode, and stands at `position` (once seen there)."""
        await self.control.set_inventory(self.name, items)
        await self.control.gamemode(self.name, self.gamemode)
        if position is None:
            return
        pos = placement.centred(position)
        await self.control.teleport(self.name, pos)
        end = time.monotonic() + ARRIVE_S
        while time.monotonic() < end:
            at = await self.where()
            if at is None or math.dist(at, pos) < 1.0:
                return
            await asyncio.sleep(0.1)

    async def observe(self) -> list:
        return [["observe", await self.observation()]]

    async def observation(self) -> Observation:
        """What the server knows of the player (its place and what it holds); the last one read while the
        person is away."""
        players = {p["name"]: p for p in await self.control.players()}
        me = players.get(self.name)
        if me is None:
            return self.last
        items: dict[str, int] = {}
        for slot in await self.control.inventory(self.name):
            items[slot["name"]] = items.get(slot["name"], 0) + slot["count"]
        x, y, z = me["pos"]
        status = {"position": {"x": x, "y": y, "z": z}, "health": me["health"], "name": self.name}
        self.last = {"status": status, "inventory": items}  # type: ignore[typeddict-item]
        return self.last


class Clients:
    """The players people play from Minecraft clients (side -> players), their joins and comebacks."""

    def __init__(self, seats: dict[str, list[str]]):
        self.side_of = {name: side for side, names in seats.items() for name in names}

    @classmethod
    def of(cls, seats: Seats) -> Clients:
        """The clients of the seats people take (people/seats.py): one per player people play."""
        out: dict[str, list[str]] = {}
        for seat in seats.seats.values():
            out.setdefault(seat.side, []).append(seat.player)
        return cls(out)

    @property
    def names(self) -> list[str]:
        return list(self.side_of)

    async def wait_joined(self, control: Control, timeout: float) -> bool:
        """Whether every person joined within `timeout` seconds (joining is being ready)."""
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            online = {p["name"] for p in await control.players()}
            if set(self.names) <= online:
                return True
            await asyncio.sleep(JOIN_POLL_S)
        return False

    async def rejoined(self, players: dict[str, Player]) -> list[str]:
        """Each second of a game: a person back in the world is put where the player was, holding what it
        held (the last look's, `ClientPlayer.last`); the players put back."""
        back = []
        for name in self.names:
            player = players.get(name)
            if not isinstance(player, ClientPlayer):
                continue
            if await player.where() is None:
                player.away = True
                continue
            if player.away:
                player.away = False
                pos = (player.last.get("status") or {}).get("position")
                await player.put(
                    dict(player.last.get("inventory") or {}), [pos["x"], pos["y"], pos["z"]] if pos else None
                )
                back.append(name)
            await player.observation()
        return back
