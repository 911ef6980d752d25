"""The lockstep clock as a match keeps it (`SidesClock`): it tells a stall of our machine from a side's own
long call (LockstepClock.stalls reads what it counts)."""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator, Sequence
from contextlib import asynccontextmanager

from pillagerbench.server.clock import LockstepClock
from pillagerbench.server.seams import Control, Events


class SidesClock(LockstepClock):
    """The lockstep clock as a match keeps it: it also counts, per player, the let-gos of its idle bot that
    came while its side held the world itself (`thinking` as the side: an LLM's or a team server's call in
    flight). Those did not let the world go on at the server's wall-clock limit (the side's own hold still
    held it); once the call ended it went on without the bot at a moment the call chose: the team's own,
    not a stall of our machine. (A seat's hold, `tools:<side>`, is not counted: the seat frees its idle
    bots as it holds the world, and its holds come and go with every tool call.)"""

    def __init__(
        self,
        server: Control,
        events: Events | None,
        per_1k: float | None,
        sides: dict[str, list[str]],
    ):
        super().__init__(server, events, per_1k)
        self.sides = sides  # side key -> its players (self.masked: player -> let-gos while its side held the world)
        self._thinking: dict[str, int] = {}  # side -> its holds on (thinking)
        self._before: dict[str, dict[str, int]] = {}  # side -> the let-gos as its first hold began

    @asynccontextmanager
    async def thinking(self, who: str) -> AsyncIterator[None]:
        tracked = not self.over and who in self.sides  # (an LLM's or a team server's hold is its side's key)
        async with super().thinking(who):
            if tracked:
                self._thinking[who] = self._thinking.get(who, 0) + 1
                if self._thinking[who] == 1:
                    self._before[who] = await self._let_gos()
            try:
                yield
            finally:
                if tracked and self._thinking.get(who):
                    self._thinking[who] -= 1
                    if not self._thinking[who] and not self.over:
                        self._mask(who, await asyncio.shield(self._let_gos()))

    async def _let_gos(self) -> dict[str, int]:
        state = await self.server.clock()
        return {who.removeprefix("idle:"): n for who, n in state.get("let_go", {}).items()}

    def _mask(self, side: str, now: dict[str, int]) -> None:
        before = self._before.pop(side, {})
        for name in self.sides[side]:
            self.masked[name] = self.masked.get(name, 0) + now.get(name, 0) - before.get(name, 0)

    async def end(self) -> None:
        await super().end()
        for side in [k for k, n in self._thinking.items() if n]:  # still thinking at the whistle
            self._mask(side, self.went_on)
        self._thinking.clear()

    async def begin(self, bystanders: Sequence[str] = ()) -> None:
        self.masked, self._thinking, self._before = {}, {}, {}
        await super().begin(bystanders)
