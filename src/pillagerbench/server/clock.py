"""Game time as the match, the game master and the teams read it (config `clock`, docs/clock.md).

`RealClock` is the wall clock. `LockstepClock` is the arena server's tick (js/server/plugins/lockstep.js):
game time is tick x 50 ms; it moves only when every bot has done the last tick and nothing holds it.
Both give `now()` (game seconds), `sleep_until(t)`, `sleep(s)`, and `thinking(who)` around a player's
LLM call (or a remote team's HTTP call): on the lockstep clock the world waits for it, and `charge`
then costs `ticks_per_1k_tokens` of game time for the tokens it generated, if set. `at(t, who)` runs a
step of the game (the game master's, a score sample) at game time `t`: on the lockstep clock at that
tick exactly, with the world held until the same step's next wait is in place. During a game a bot whose run has ended
holds the world (`idle:NAME`) until its next run begins or its team `rest`s it (a wait, exact to the
tick), so the next program starts at the tick the last one ended; `retire` once its team's play is over. `end()` at the whistle drops every hold
(stopping the players needs ticks); `begin()` before the next game.
"""

from __future__ import annotations

import asyncio
import math
import time
from collections.abc import AsyncIterator, Sequence
from contextlib import AbstractAsyncContextManager, asynccontextmanager
from typing import Protocol

from pillagerbench.config.game_tick import TICK_S
from pillagerbench.server.seams import Control, Events

CLOCK_EVENT = "clock"  # the event the server pushes with its tick (not a world event)


class GameClock(Protocol):
    mode: str

    def now(self) -> float: ...

    async def sleep_until(self, t: float) -> None: ...

    async def sleep(self, seconds: float) -> None: ...

    def thinking(self, who: str) -> AbstractAsyncContextManager[None]: ...

    def at(self, t: float, who: str) -> AbstractAsyncContextManager[None]: ...

    async def rest(self, players: list[str], seconds: float) -> None: ...

    async def charge(self, tokens: int, players: list[str]) -> None: ...

    async def let_go(self, who: str) -> None: ...

    async def retire(self, players: list[str]) -> None: ...

    async def hold_idle(self, player: str) -> None: ...

    async def free_idle(self, players: list[str]) -> None: ...

    async def pace(self, speed: float | str) -> None: ...

    async def begin(self, bystanders: Sequence[str] = ()) -> None: ...

    async def end(self) -> None: ...

    async def close(self) -> None: ...

    def saw(self, tick: int | None) -> None: ...

    def stalls(self, problems: dict[str, list[str]]) -> list[str]: ...


async def _forever() -> None:
    await asyncio.Event().wait()


class RealClock:
    """The wall clock (clock=real): what every episode played on before lockstep."""

    mode = "real"

    def now(self) -> float:
        return time.monotonic()

    async def sleep_until(self, t: float) -> None:
        await self.sleep(t - time.monotonic())

    async def sleep(self, seconds: float) -> None:
        await (asyncio.sleep(max(0.0, seconds)) if math.isfinite(seconds) else _forever())

    @asynccontextmanager
    async def thinking(self, who: str) -> AsyncIterator[None]:
        yield

    @asynccontextmanager
    async def at(self, t: float, who: str) -> AsyncIterator[None]:
        await self.sleep_until(t)
        yield

    async def rest(self, players: list[str], seconds: float) -> None:
        await self.sleep(seconds)

    async def charge(self, tokens: int, players: list[str]) -> None:
        return None

    async def let_go(self, who: str) -> None:
        return None

    async def retire(self, players: list[str]) -> None:
        return None

    async def hold_idle(self, player: str) -> None:
        return None

    async def free_idle(self, players: list[str]) -> None:
        return None

    async def pace(self, speed: float | str) -> None:
        """The wall clock has one pace."""
        return None

    async def begin(self, bystanders: Sequence[str] = ()) -> None:
        return None

    async def end(self) -> None:
        return None

    async def close(self) -> None:
        return None

    def saw(self, tick: int | None) -> None:
        return None

    def stalls(self, problems: dict[str, list[str]]) -> list[str]:
        """The wall clock never stops the world: nothing of a game is the clock's doing."""
        return []


class LockstepClock:
    """The arena server's lockstep tick (clock=lockstep). `start()` before use, `close()` after."""

    mode = "lockstep"

    def __init__(
        self,
        server: Control,
        events: Events | None,
        ticks_per_1k_tokens: float | None = None,
    ):
        self.server = server
        self.events = events
        self.ticks_per_1k_tokens = ticks_per_1k_tokens
        self.tick = 0
        self.over = False  # after the whistle thinking holds the world no more
        self._held: dict[str, int] = {}  # who -> holds of thinking() still on
        self._stepping: set[str] = set()  # who holds the world since its last at(), until its next
        # player -> how many times in the last game the server let go of its idle bot (its team neither ran
        # nor rested it within the server's wall-clock limit): that game may not repeat under its seed
        self.went_on: dict[str, int] = {}
        # the game's players by side, and per player the let-gos that came while its side held the world itself
        # (counted by match/sides_clock.py): those are the side's own, not a stall of our machine
        self.sides: dict[str, list[str]] = {}
        self.masked: dict[str, int] = {}
        self._queue: asyncio.Queue | None = None
        self._follow: asyncio.Task | None = None

    async def start(self) -> LockstepClock:
        state = await self.server.clock()
        if state["mode"] != "lockstep":
            raise RuntimeError(f"the arena server runs on the {state['mode']} clock, not lockstep")
        self._seen(state["tick"])
        if self.events is not None:
            self._queue = self.events.subscribe()
            self._follow = asyncio.create_task(self._read(self._queue), name="lockstep-clock")
        return self

    async def _read(self, queue: asyncio.Queue) -> None:
        while True:
            ev = await queue.get()
            if ev.get("event") == CLOCK_EVENT:
                self._seen(int(ev["tick"]))

    def _seen(self, tick: int) -> None:
        self.tick = max(self.tick, tick)

    def saw(self, tick: int | None) -> None:
        """A tick the world was at (a run's end, told by its bot)."""
        if tick is not None:
            self._seen(tick)

    async def close(self) -> None:
        if self._follow is not None:
            self._follow.cancel()
        if self._queue is not None and self.events is not None:
            self.events.unsubscribe(self._queue)

    def now(self) -> float:
        return self.tick * TICK_S

    @staticmethod
    def tick_of(t: float) -> int:
        """The first tick at or after game time `t`."""
        return math.ceil(round(t / TICK_S, 6))

    async def sleep_until(self, t: float) -> None:
        if not math.isfinite(t):
            await _forever()
        self._seen(await self.server.wait_tick(self.tick_of(t)))

    async def sleep(self, seconds: float) -> None:
        await self.sleep_until(self.now() + max(0.0, seconds))

    @asynccontextmanager
    async def thinking(self, who: str) -> AsyncIterator[None]:
        if self.over:
            yield
            return
        self._held[who] = self._held.get(who, 0) + 1
        self._seen(await self.server.hold(who))
        try:
            yield
        finally:
            if self._held.get(who, 0) > 0:  # not released by end() meanwhile
                self._held[who] -= 1
                await asyncio.shield(self.server.release(who))

    @asynccontextmanager
    async def at(self, t: float, who: str) -> AsyncIterator[None]:
        """The step runs at `t`'s tick with the world held, and the hold stays on after it: `who`'s next
        `at` hands it on to its own tick in one op (the wait is in place before the world goes on, so
        however late Python sends it, the next step is not late). The whistle (`end`) drops it."""
        if self.over:  # after the whistle: held for the step only (nothing hands it on)
            self._seen(await self.server.wait_tick(self.tick_of(t), hold=who))
            try:
                yield
            finally:
                await asyncio.shield(self.server.release(who))
            return
        handed = who if who in self._stepping else None
        self._stepping.add(who)
        self._seen(await self.server.wait_tick(self.tick_of(t), hold=who, release=handed))
        yield

    async def rest(self, players: list[str], seconds: float) -> None:
        """These players' bots, idle since their last run, wait `seconds` of game time: their holds go
        and come back on the tick that ends the wait (one op, so that tick is exact however long
        Python takes), when their team's next step begins."""
        if not math.isfinite(seconds):
            await self.retire(players)
            await _forever()
        self._seen(await self.server.rest(players, self.tick_of(max(0.0, seconds))))

    async def let_go(self, who: str) -> None:
        """`who`'s steps are over (its loop has ended): the hold its last `at` left on goes."""
        if who in self._stepping:
            self._stepping.discard(who)
            await asyncio.shield(self.server.release(who))

    async def retire(self, players: list[str]) -> None:
        """These players' team has nothing more for them this game (its play is over): they hold the world
        no more, not even as a run of theirs ends, until the whistle."""
        if not self.over:
            self._seen(await self.server.retire(players))

    async def hold_idle(self, player: str) -> None:
        """`player`'s bot holds the world as if idle until its next run (or rest) begins: a run started from
        now on starts on this tick, however long its request takes to reach the bot (the seat's tool calls)."""
        if not self.over:
            self._seen(await self.server.hold(f"idle:{player}"))

    async def free_idle(self, players: list[str]) -> None:
        """These players' bots, whose runs have ended, hold the world no more until their next run ends (a
        seat's team holds it instead while its agent thinks, or its other players act); the server ignores
        an ended run's IDLE that reaches it after this."""
        if not self.over:
            self._seen(await self.server.free(players))

    async def charge(self, tokens: int, players: list[str]) -> None:
        """Thinking charged in game time: the team's players wait it out."""
        if self.ticks_per_1k_tokens and tokens > 0 and not self.over:
            await self.rest(players, tokens / 1000 * self.ticks_per_1k_tokens * TICK_S)

    async def end(self) -> None:
        self.over = True
        self._held.clear()
        self._stepping.clear()
        state = await self.server.clock(
            drop_holds=True, game=False
        )  # a step cancelled at the whistle may still be due a hold
        self.went_on = {who.removeprefix("idle:"): n for who, n in state.get("let_go", {}).items()}

    async def pace(self, speed: float | str) -> None:
        """How fast game time passes on the wall: a game's ("max", or times real time; config clock.speed),
        and real time's between games (1.0), so idle bots cost no CPU. Asked before `begin` and after `end`,
        as the match always did (inside them, an episode after the first did not repeat under its seed)."""
        await self.server.clock(unpaced=True) if speed == "max" else await self.server.clock(speed=float(speed))

    async def begin(self, bystanders: Sequence[str] = ()) -> None:
        """A new game: thinking holds the world again, and so does a bot whose run has ended.
        `bystanders`: players no team plays (Dash & Dine's servers), whose bots never run: they hold
        nothing (held, each would stop the world for the 5 s of wall time the server allows)."""
        self.over = False
        self._stepping.clear()
        self._seen((await self.server.clock(drop_holds=True, game=True))["tick"])  # every bot idle: held
        for name in bystanders:
            await self.server.release(f"idle:{name}")

    def stalls(self, problems: dict[str, list[str]]) -> list[str]:
        """The last game's let-gos of idle bots at the server's wall-clock limit, as stalls of our machine; one
        that came while the bot's side held the world itself (a call of its longer than the limit) is that
        side's own problem instead (added to `problems`), as a seat's think limit is."""
        reasons = []
        for name, n in self.went_on.items():
            own = min(n, max(0, self.masked.get(name, 0)))
            if n > own:
                reasons.append(
                    f"lockstep: {name} idle, neither run nor rested, and the world went on without it after the "
                    f"server's wall-clock limit ({n - own}x): this game may not repeat under its seed"
                )
            side = next((k for k, names in self.sides.items() if name in names), None)
            if own and side:
                problems.setdefault(side, []).append(
                    f"lockstep: {name} idle while its team held the world past the server's wall-clock limit "
                    f"({own}x): once the team's call ended the world went on without it; this game may not repeat "
                    "under its seed"
                )
        return reasons
