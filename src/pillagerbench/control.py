"""The seams to the arena server, as the game master, the players and the match see it: small
Protocols, so that each side names what it uses (the arena's `ArenaServer` is the one real
implementation; `arena/server.py`)."""

from __future__ import annotations

import asyncio
from typing import Any, Protocol


class Control(Protocol):
    """The control channel: one request, one answer (game masters, arenas, players' server checks)."""

    async def request(self, op: str, **args: Any) -> Any: ...


class Events(Protocol):
    """What the server pushes (chat, refusals, ...): a queue per subscriber."""

    def subscribe(self) -> asyncio.Queue: ...

    def unsubscribe(self, q: asyncio.Queue) -> None: ...


class Server(Control, Protocol):
    """A running arena server as a match uses it."""

    port: int | None
    watch_url: str | None

    @property
    def control(self) -> Events | None: ...

    @property
    def alive(self) -> bool: ...

    async def start(self) -> Any: ...

    async def stop(self) -> None: ...
