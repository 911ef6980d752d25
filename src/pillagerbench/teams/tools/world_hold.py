"""Game time for a seated team on the lockstep clock (docs/any-agent.md): the world waits while the agent
thinks. While none of the team's acting calls is in flight the team holds the world (`tools:<side>`, a
hold with no wall-clock limit); an acting call lets it run until it returns (two in flight, while either
is). A call that ends stops the world on the tick it ended (its bot's idle hold), so the next call starts
there however long the agent took; the acting calls that arrive within `window_s` of wall time while the
world is held (one model turn's) start on the same tick. On the real clock every step here is a no-op:
the world runs on, as for every team.
"""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator, Sequence
from contextlib import AsyncExitStack, asynccontextmanager

from pillagerbench.teams.base import TeamContext


class WorldHold:
    def __init__(self, side: str, players: list[str], window_s: float = 0.05):
        self.side, self.players, self.window_s = side, players, window_s
        self._lock = asyncio.Lock()  # one change of the world's holds at a time
        self._busy: dict[str, int] = {}  # player -> its acting calls in flight
        self._hold: AsyncExitStack | None = None  # the team's hold while nothing acts (lockstep)
        self._go: asyncio.Task | None = None  # lets the world go once the turn's window has passed

    @property
    def thinking(self) -> bool:
        """The team holds the world and nothing of it acts: its agent is thinking."""
        return self._hold is not None and not any(self._busy.values())

    async def start(self, ctx: TeamContext) -> None:
        """The game begins with the world held until the agent's first acting call."""
        async with self._lock:
            await self._hold_world(ctx)

    async def stop(self) -> None:
        """The whistle (which drops every hold of the server's anyway)."""
        await self._let_world_go()

    async def let_go(self, ctx: TeamContext) -> None:
        """For good this game (the agent left, or thinks too long): the world goes on without the team."""
        async with self._lock:
            await self._let_world_go()
            await ctx.clock.retire(self.players)

    @asynccontextmanager
    async def acting(self, ctx: TeamContext, players: Sequence[str], *, again: bool = True) -> AsyncIterator[None]:
        """Around one acting call of these players. `again`: once nothing acts, the team holds the world."""
        for player in players:
            await self._begin(ctx, player)
        try:
            yield
        finally:
            for player in players:
                await self._end(ctx, player, again)

    async def _begin(self, ctx: TeamContext, player: str) -> None:
        async with self._lock:
            first = not any(self._busy.values())
            self._busy[player] = self._busy.get(player, 0) + 1
            await ctx.clock.hold_idle(player)  # until its run (or wait) begins: it starts on this tick
            if first and self._hold is not None and self._go is None:
                self._go = asyncio.create_task(self._go_after_window())

    async def _go_after_window(self) -> None:
        await asyncio.sleep(self.window_s)  # the turn's other calls start on the same tick
        async with self._lock:
            self._go = None
            if any(self._busy.values()):
                await self._let_world_go()

    async def _end(self, ctx: TeamContext, player: str, again: bool) -> None:
        async with self._lock:
            self._busy[player] -= 1
            if self._busy[player] == 0 and any(self._busy.values()):
                await ctx.clock.free_idle([player])  # the others still act: the world goes on for them
            elif not any(self._busy.values()) and ctx.time_left() > 0 and again:
                await self._hold_world(ctx)  # stopped on the tick this call ended; held while the agent thinks

    async def _hold_world(self, ctx: TeamContext) -> None:
        if ctx.clock.mode != "lockstep" or self._hold is not None:
            return
        stack = AsyncExitStack()
        await stack.enter_async_context(ctx.clock.thinking(f"tools:{self.side}"))
        self._hold = stack
        await ctx.clock.free_idle(self.players)  # the team's hold has no wall-clock limit; idle holds do

    async def _let_world_go(self) -> None:
        stack, self._hold = self._hold, None
        if stack is not None:
            await stack.aclose()
