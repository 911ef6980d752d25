"""The Python handle of one player, as the match and its team use it: run agent code, stop it, observe,
measure the bot's lag, reset it for an episode. Its bot process's life (launch, login, the watchdog,
restarts) is `BotProcess` (bot_process.py), which the player holds as `bot`.

    async with ArenaServer() as server:
        player = Player("Ryn", server.port, server=server)
        await player.start()
        await player.reset(position=(-7, 4, -10), inventory={"bread": 2})
        events = await player.run("await mineBlock(bot, 'slime_block', 2)")
        assert events[-1][0] == "observe"
        await player.close()

A run that the bot's restart interrupts (its code blocked the bot, the process died, it did not stop in
time) ends with an onError event and the observation after the restart.
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable, Sequence
from pathlib import Path

from pillagerbench.server.seams import Control

from . import placement
from .bot_process import BotProcess, PendingRun
from .channel import BotChannel, PlayerError

__all__ = ["Player", "PlayerError"]

STOP_WAIT_S = 2.0  # a bot told to stop has this long to end its run, or it is restarted


class Player:
    def __init__(
        self,
        name: str,
        server_port: int,
        *,
        host: str = "127.0.0.1",
        log_dir: Path | None = None,
        primitives: list[str] | None = None,
        server: Control | None = None,
        watchdog_s: float = 1.0,
        login_timeout: float = 30.0,
        clock: str = "real",
        view: bool = False,
    ):
        self.name = name
        self.clock = clock  # "real" or "lockstep": the bot's timers on the wall clock or the server's ticks
        self.last_tick: int | None = None  # lockstep: the server's tick when the last run ended
        self.server = server  # the arena's control channel (None: no server-side checks)
        self.bot = BotProcess(
            name,
            server_port,
            host=host,
            log_dir=Path(log_dir) if log_dir else None,
            primitives=list(primitives) if primitives is not None else None,
            server=server,
            watchdog_s=watchdog_s,
            login_timeout=login_timeout,
            clock=clock,
            view=view,
        )
        self._run_lock = asyncio.Lock()

    async def launch(self) -> None:
        """Start the bot process, to log in at `start` (a match launches all its players at once)."""
        await self.bot.launch()

    async def start(self) -> None:
        """Start the bot (unless `launch` has) and log it in."""
        await self.bot.start()

    @property
    def channel(self) -> BotChannel:
        """The bot's requests (its current process's: a restart starts a new one)."""
        return self.bot.channel

    def _control(self) -> Control:
        if self.server is None:
            raise PlayerError(f"{self.name}: this needs `server=` (the arena's control channel)")
        return self.server

    async def run(
        self, code: str, *, timeout: float | None = None, on_event: Callable[[list], None] | None = None
    ) -> list:
        """Run agent code; return its events, ending with ["observe", {...}]. Events also go to
        `on_event` as they happen."""
        async with self._run_lock:
            await self.bot.restarted()
            if not self.bot.alive:
                raise PlayerError(f"{self.name}: the bot is not running (call start())")
            rid = self.bot.channel.next_id()
            state = PendingRun(rid, on_event)
            self.bot.pending = state
            try:
                try:
                    await self.bot.channel.run(code, timeout or None, rid=rid)
                except PlayerError as exc:
                    state.add(["onError", {"onError": str(exc)}])
                    return state.events
                self.last_tick = _tick_of(await state.done)
                await self.bot.restarted()  # a restart finishing: its events are already in
                return state.events
            finally:
                self.bot.pending = None

    async def stop(self) -> None:
        """Stop running code at once; the pending run() returns promptly."""
        run = self.bot.pending
        if run is None or run.done.done():
            return
        try:
            await self.bot.channel.stop()
        except PlayerError:
            return
        try:
            await asyncio.wait_for(asyncio.shield(run.done), STOP_WAIT_S)
        except asyncio.TimeoutError:
            await self.bot.restart(
                f"Error: the bot did not stop within {STOP_WAIT_S:g} s and was restarted",
                f"{self.name} did not stop within {STOP_WAIT_S:g} s and was restarted",
                self.bot.generation,
            )

    async def observe(self) -> list:
        return [["observe", await self.bot.observe()]]

    async def lag(self, *, reset: bool = False) -> dict:
        """How late this bot's 50 ms physics ticks were since the last `lag(reset=True)`, measured in
        the bot process (js/bot/lag.js): ticks, wall_s, tick_rate, late_mean_ms, late_max_ms, late_pct."""
        found = await self.bot.channel.lag(reset=reset)
        return dict(found) if isinstance(found, dict) else {}

    async def reset(
        self,
        *,
        position: Sequence[float] | None = None,
        inventory: dict[str, int] | None = None,
        equipment: placement.Equipment = None,
        seed: int | None = None,
    ) -> list:
        """Stop code, then set inventory/equipment/position (through the control channel) and return
        [["observe", {...}]]; events from before are dropped. `seed`: the episode's (the bot's chance)."""
        await self.stop()
        async with self._run_lock:
            if not self.bot.alive:
                await self.bot.relogin()
            needs_server = inventory is not None or position is not None or equipment is not None
            if needs_server and self.server is None:
                raise PlayerError(
                    f"{self.name}: reset with inventory/position/equipment needs `server=` (the arena's control channel)"
                )
            if inventory is not None or equipment is not None:
                items = placement.reset_items(inventory, equipment)
                await self._control().set_inventory(self.name, items)
            if position is not None:
                await placement.reset_to(self._control(), self.bot.channel, self.name, position, self.clock)
            if equipment is not None:
                await placement.wait_inventory(self.bot.observe, inventory or {}, equipment)
                await self.bot.channel.equip(equipment, wait=15)
            await self.bot.channel.clear(seed)
            return await self.observe()

    async def close(self) -> None:
        self.bot.closed = True  # no restart from here on
        if self.bot.pending is not None:
            await self.stop()
        await self.bot.close()

    async def __aenter__(self) -> Player:
        await self.start()
        return self

    async def __aexit__(self, *exc) -> None:
        await self.close()


def _tick_of(answer: object) -> int | None:
    """The server's tick a run's answer names (the lockstep clock), else None."""
    tick = (answer.get("result") or {}).get("tick") if isinstance(answer, dict) else None
    return tick if isinstance(tick, int) else None
