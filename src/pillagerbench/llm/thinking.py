"""Where a team's LLM calls stand on the game clock. The match sets `hold` and `charge` for the game
(server/clock.py: on the lockstep clock the world waits while a call is in flight, then is charged
`ticks_per_1k_tokens` for what it generated) and clears them at the whistle; otherwise (pre-game,
post-game, the real clock, no match) a call is just a call."""

from __future__ import annotations

from collections.abc import AsyncIterator, Awaitable, Callable
from contextlib import AbstractAsyncContextManager, asynccontextmanager


class Thinking:
    def __init__(self) -> None:
        self.hold: Callable[[], AbstractAsyncContextManager[None]] | None = None
        self.charge: Callable[[int], Awaitable[None]] | None = None

    def during_game(
        self, hold: Callable[[], AbstractAsyncContextManager[None]], charge: Callable[[int], Awaitable[None]]
    ) -> None:
        self.hold, self.charge = hold, charge

    def after_game(self) -> None:
        self.hold = self.charge = None

    @asynccontextmanager
    async def held(self) -> AsyncIterator[None]:
        """Around one call."""
        if self.hold is None:
            yield
        else:
            async with self.hold():
                yield

    async def charged(self, tokens: int | None) -> None:
        """After one call: its generated tokens' game time, if charged."""
        if self.charge is not None and tokens:
            await self.charge(tokens)
