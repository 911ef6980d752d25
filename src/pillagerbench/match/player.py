"""The player handle a team gets in an episode."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from pillagerbench.players import Player
from pillagerbench.server.clock import GameClock, RealClock


class RecordedPlayer:
    """A player handle that also appends every event of its runs to the episode's log, counts the
    runs started, waits `step_wait_s` before and after each run (upstream's step, protocol=upstream)
    and tells `on_program(player, what, message)` when each program starts, fails and ends (the replay)."""

    def __init__(
        self,
        player: Player,
        sink: Callable[[str, list], None],
        runs: dict[str, int] | None = None,
        *,
        step_wait_s: float = 0.0,
        on_program: Callable[[str, str, str | None], None] | None = None,
        clock: GameClock | None = None,
    ):
        self._player, self._sink = player, sink
        self._clock = clock or RealClock()  # the step waits are game time
        self._runs = {} if runs is None else runs  # code runs started per player this episode
        self._wait, self._on_program = step_wait_s, on_program

    def __getattr__(self, name: str) -> Any:
        return getattr(self._player, name)

    async def _pause(self) -> None:
        await self._clock.rest([self._player.name], self._wait)  # lockstep: its bot, idle since its last run, waits

    def _program(self, what: str, message: str | None = None) -> None:
        if self._on_program is not None:
            self._on_program(self._player.name, what, message)

    def note(self, event: list) -> None:
        """An event of the player's that no run made (a tool call refused: teams/tools/seat.py), in its log."""
        self._sink(self._player.name, event)

    async def run(self, code: str, *, timeout: float | None = None, on_event=None) -> list:
        def both(event):
            self._sink(self._player.name, event)
            if isinstance(event, list) and event and event[0] == "onError":
                self._program("error", str((event[1] or {}).get("onError", "")) if len(event) > 1 else "")
            if on_event:
                on_event(event)

        if self._wait:
            await self._pause()  # upstream's step: the wait before the code (cancelled at the whistle)
        self._runs[self._player.name] = self._runs.get(self._player.name, 0) + 1
        self._program("start")
        try:
            events = await self._player.run(code, timeout=timeout, on_event=both)
        finally:
            self._program("end")
        self._clock.saw(getattr(self._player, "last_tick", None))  # lockstep: now() is the tick the run ended
        if self._wait:
            await self._pause()  # and the wait after it, before the step returns
        return events
