"""The Python handle of one player: a bot process (Node, mineflayer) that runs agent code.

    async with ArenaServer() as server:
        player = Player("Ryn", server.port, server=server)
        await player.start()
        await player.reset(position=(-7, 4, -10), inventory={"bread": 2})
        events = await player.run("await mineBlock(bot, 'slime_block', 2)")
        assert events[-1][0] == "observe"
        await player.close()

The bot process speaks JSON lines over stdio, declared in js/bot/bot_protocol.json (bot_protocol.py: the
typed ops and settings; channel.py holds the process and its requests, placement.py sets and restores
inventory and position). It writes a heartbeat every 200 ms; when it stays silent for `watchdog_s`
(agent code blocking its event loop), or dies, the handle kills its process group, logs in again with
the same name, restores inventory and position through the control channel (when `server` is given)
and ends the pending run with an onError event.

A silent bot is told apart by the CPU time its process got while silent (from the watchdog's last look
while it spoke, which comes after its last heartbeat, to the verdict): a loop in its code burns a core
(its fair share of one, on a busy machine); a bot stopped or starved by the machine got next to none
(under `STARVED_SHARE` of a core), and that restart is ours, not the code's: `Watchdog` keeps it in its
`stalls` with a bot that did not stop within 2 s, and the match records them (the episode is spoiled).
"""

from __future__ import annotations

import asyncio
import time
from collections.abc import Callable, Sequence
from pathlib import Path

import psutil

from pillagerbench.server.seams import Control

from . import placement
from .bot_protocol import Settings
from .channel import BotChannel, PlayerError
from .observation import Observation, observation

__all__ = ["Player", "PlayerError"]

# One login at a time per server (flying-squid handles concurrent logins badly), with a short gap.
_login_locks: dict[tuple[str, int], asyncio.Lock] = {}
LOGIN_GAP_S = 0.05
# A bot silent past its watchdog whose process got less than this share of one core meanwhile was
# starved (stopped, or the machine gave it no time), not looping: a loop burns its fair share of a core
# (all of one on a calm machine; 0.28 to 0.41 on 2 cores beside 4 CPU-bound processes, docs/performance.md),
# a stopped bot none. A tenth: a loop still gets it beside 19 busy processes on 2 cores.
STARVED_SHARE = 0.1
STOP_WAIT_S = 2.0  # a bot told to stop has this long to end its run, or it is restarted
Cpu = tuple[float, float, int]  # a process's CPU time read: (monotonic then, its CPU seconds, its pid)


class _RunState:
    def __init__(self, rid: int, on_event: Callable[[list], None] | None):
        self.rid = rid
        self.events: list[list] = []
        self.on_event = on_event
        self.done: asyncio.Future = asyncio.get_running_loop().create_future()

    def add(self, event: list) -> None:
        self.events.append(event)
        if self.on_event is not None:
            try:
                self.on_event(event)
            except Exception:  # noqa: BLE001 - a faulty callback must not break the run
                pass


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
        self.name, self.server_port, self.host = name, server_port, host
        self.view = view  # a person's player: its bot can serve the first-person view (js/bot/view.js)
        self.clock = clock  # "real" or "lockstep": the bot's timers on the wall clock or the server's ticks
        self.last_tick: int | None = None  # lockstep: the server's tick when the last run ended
        self.log_dir = Path(log_dir) if log_dir else None
        self.primitives = list(primitives) if primitives is not None else None
        self.server = server  # the arena's control channel (None: no server-side checks)
        self.watchdog_s = watchdog_s
        self.login_timeout = login_timeout
        self.restarts = 0
        self.watchdog = Watchdog(self)  # its silence judged: the code's or the machine's (a stall)
        self.channel = BotChannel(name, self.log_dir)
        self._run: _RunState | None = None
        self._run_lock = asyncio.Lock()
        self._recover_lock = asyncio.Lock()
        self._spawned: asyncio.Future | None = None
        self._awaits_cue = False  # a process is launched and not yet cued to log in
        self._tasks: list[asyncio.Task] = []
        self._recoveries: set[asyncio.Task] = set()  # held so a running recovery is not garbage-collected
        self._fatal: str | None = None
        self._closed = False
        self._generation = 0
        self.position: list[float | None] | None = None
        self._last_obs: Observation = {}  # the last seen: a restart restores from it when the server cannot say

    # ---- process ----------------------------------------------------------------------------
    @property
    def proc(self) -> asyncio.subprocess.Process | None:
        """The bot process (the current one: a restart starts a new one)."""
        return self.channel.proc

    @property
    def alive(self) -> bool:
        return (
            self.proc is not None
            and self.proc.returncode is None
            and self._spawned is not None
            and self._spawned.done()
            and not self._spawned.exception()
        )

    async def start(self) -> None:
        """Spawn the bot process (unless `launch` has), log in and wait until it has spawned."""
        if not self._awaits_cue:
            await self.launch()
        async with _login_locks.setdefault((self.host, self.server_port), asyncio.Lock()):
            await self._login()
            await asyncio.sleep(LOGIN_GAP_S)

    async def launch(self) -> None:
        """Start the bot process: it loads its libraries, then waits for its cue to log in (`start`).
        A match launches all its players at once, so that this overlaps the logins, one at a time."""
        settings = Settings(host=self.host, port=self.server_port, username=self.name, primitives=self.primitives)
        settings |= {"heartbeatMs": 200, "clock": self.clock, "cue": True}  # cue: it logs in at _login's
        if self.view:
            settings["view"] = True
        loop = asyncio.get_running_loop()
        self._generation += 1
        self._spawned = loop.create_future()
        self._fatal = None
        proc = await self.channel.spawn(settings)
        self._awaits_cue = True
        gen = self._generation
        self._tasks = [t for t in self._tasks if not t.done()]
        self._tasks.append(asyncio.create_task(self._read_stdout(proc, gen)))
        self._tasks.append(asyncio.create_task(self.channel.read_stderr(proc)))
        if not any(t.get_name() == f"watchdog-{self.name}" and not t.done() for t in self._tasks):
            self._tasks.append(asyncio.create_task(self.watchdog.run(), name=f"watchdog-{self.name}"))

    async def _login(self) -> None:
        """Cue the launched bot to connect; wait until it has spawned."""
        if self._spawned is None:
            raise PlayerError(f"{self.name}: no bot process to log in (launch() first)")
        self._awaits_cue = False
        await self.channel.cue()
        try:
            await asyncio.wait_for(asyncio.shield(self._spawned), self.login_timeout)
        except asyncio.TimeoutError:
            await self.channel.kill()
            raise PlayerError(
                f"{self.name}: bot did not spawn within {self.login_timeout} s\n{self.channel.stderr_tail()}"
            ) from None
        except PlayerError:
            await self.channel.kill()
            raise

    async def _read_stdout(self, proc: asyncio.subprocess.Process, gen: int) -> None:
        try:
            await self.channel.read_stdout(proc, self._dispatch)
        finally:
            if gen == self._generation and not self.channel.expect_exit and not self._closed:
                reason = self._fatal or self.channel.exit_reason(proc.returncode)
                if self._spawned and not self._spawned.done():
                    self._spawned.set_exception(
                        PlayerError(f"{self.name}: bot process ended before spawning: {reason}")
                    )
                else:
                    task = asyncio.create_task(self._recover(reason, None, gen))
                    self._recoveries.add(task)
                    task.add_done_callback(self._recoveries.discard)

    def _dispatch(self, msg: dict) -> None:
        if "hb" in msg:
            return
        if "ev" in msg:
            run = self._run
            if isinstance(msg["ev"], list) and len(msg["ev"]) == 2 and isinstance(msg["ev"][1], dict):
                self._last_obs = observation(msg["ev"][1])  # an event's data is an observation and its own key
            if run is not None and msg.get("run") == run.rid:
                run.add(msg["ev"])
            return
        if "spawned" in msg:
            pos = msg["spawned"].get("position") or {}
            self.position = [pos.get("x"), pos.get("y"), pos.get("z")]
            if self._spawned and not self._spawned.done():
                self._spawned.set_result(msg["spawned"])
            return
        if "fatal" in msg:
            self._fatal = f"Error: the bot lost its connection ({msg['fatal']}) and was restarted"
            return
        run = self._run
        if run is not None and msg.get("id") == run.rid:
            if not run.done.done():
                run.done.set_result(msg)
            return
        self.channel.answer(msg)

    async def _observe(self) -> Observation:
        """The bot's observation now (the `observe` request), kept as the last one seen."""
        self._last_obs = observation(await self.channel.observe())
        return self._last_obs

    # ---- watchdog and recovery -------------------------------------------------------------
    async def _recover(self, reason: str, stall: str | None, gen: int) -> None:
        """Kill (if needed), log in again, restore state, and end the pending run with onError. `stall`: the
        restart is the machine's fault (the watchdog keeps it for the match)."""
        async with self._recover_lock:
            if gen != self._generation or self._closed:
                return
            self.watchdog.stalls += [stall] if stall else []
            saved = await placement.snapshot(self.server, self.name, self._last_obs)
            await self.channel.kill()
            self.channel.fail_pending(reason)
            self.restarts += 1
            obs: Observation = {}
            try:
                await self._relogin()
                await placement.restore(self.server, self.channel, self.name, saved)
                obs = await self._observe()
            except Exception as exc:  # noqa: BLE001 - report it in the run's events
                reason = f"{reason}; restarting failed: {exc}"
            run = self._run
            if run is not None and not run.done.done():
                run.add(["onError", {**obs, "onError": reason}])
                run.add(["observe", obs])
                run.done.set_result({"id": run.rid, "ok": True, "recovered": True})

    async def _relogin(self) -> None:
        last: Exception | None = None
        for attempt in range(5):
            try:
                lock = _login_locks.setdefault((self.host, self.server_port), asyncio.Lock())
                async with lock:
                    await self.launch()
                    await self._login()
                return
            except PlayerError as exc:
                last = exc
                await asyncio.sleep(0.3 * (attempt + 1))
        raise PlayerError(f"{self.name}: could not log in again: {last}")

    def _control(self) -> Control:
        if self.server is None:
            raise PlayerError(f"{self.name}: this needs `server=` (the arena's control channel)")
        return self.server

    # ---- the API ------------------------------------------------------------------------------
    async def run(
        self, code: str, *, timeout: float | None = None, on_event: Callable[[list], None] | None = None
    ) -> list:
        """Run agent code; return its events, ending with ["observe", {...}]. Events also go to
        `on_event` as they happen."""
        async with self._run_lock:
            if self._recover_lock.locked():
                async with self._recover_lock:
                    pass
            if not self.alive:
                raise PlayerError(f"{self.name}: the bot is not running (call start())")
            rid = self.channel.next_id()
            state = _RunState(rid, on_event)
            self._run = state
            try:
                try:
                    await self.channel.run(code, timeout or None, rid=rid)
                except PlayerError as exc:
                    state.add(["onError", {"onError": str(exc)}])
                    return state.events
                self.last_tick = _tick_of(await state.done)
                if self._recover_lock.locked():  # recovery finishing: its events are already in
                    async with self._recover_lock:
                        pass
                return state.events
            finally:
                self._run = None

    async def stop(self) -> None:
        """Stop running code at once; the pending run() returns promptly."""
        run = self._run
        if run is None or run.done.done():
            return
        try:
            await self.channel.stop()
        except PlayerError:
            return
        try:
            await asyncio.wait_for(asyncio.shield(run.done), STOP_WAIT_S)
        except asyncio.TimeoutError:
            await self._recover(
                f"Error: the bot did not stop within {STOP_WAIT_S:g} s and was restarted",
                f"{self.name} did not stop within {STOP_WAIT_S:g} s and was restarted",
                self._generation,
            )

    async def observe(self) -> list:
        return [["observe", await self._observe()]]

    async def lag(self, *, reset: bool = False) -> dict:
        """How late this bot's 50 ms physics ticks were since the last `lag(reset=True)`, measured in
        the bot process (js/bot/lag.js): ticks, wall_s, tick_rate, late_mean_ms, late_max_ms, late_pct."""
        found = await self.channel.lag(reset=reset)
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
            if not self.alive:
                await self._relogin()
            needs_server = inventory is not None or position is not None or equipment is not None
            if needs_server and self.server is None:
                raise PlayerError(
                    f"{self.name}: reset with inventory/position/equipment needs `server=` (the arena's control channel)"
                )
            if inventory is not None or equipment is not None:
                items = placement.reset_items(inventory, equipment)
                await self._control().set_inventory(self.name, items)
            if position is not None:
                await placement.reset_to(self._control(), self.channel, self.name, position, self.clock)
            if equipment is not None:
                await placement.wait_inventory(self._observe, inventory or {}, equipment)
                await self.channel.equip(equipment, wait=15)
            await self.channel.clear(seed)
            return await self.observe()

    async def close(self) -> None:
        self._closed = True
        if self._run is not None:
            await self.stop()
        await self.channel.close()
        for t in self._tasks:
            if not t.done():
                t.cancel()
        self._tasks.clear()

    async def __aenter__(self) -> Player:
        await self.start()
        return self

    async def __aexit__(self, *exc) -> None:
        await self.close()


class Watchdog:
    """Python's watchdog of one player's bot, which writes a heartbeat every 200 ms: silent for the player's
    `watchdog_s`, the bot is restarted, its silence put on its code (an endless loop) or, when its process
    got under STARVED_SHARE of a core meanwhile, on the machine. The machine's restarts (those, and a bot
    that did not stop in time) are `stalls`, kept until the match takes them (`take_stalls`)."""

    def __init__(self, player: Player):
        self.player = player  # (the module's own: its recovery, its lock and generation)
        self.stalls: list[str] = []
        self._mark: Cpu | None = None  # the bot's process as it last spoke

    async def run(self) -> None:
        p = self.player
        while not p._closed:
            await asyncio.sleep(0.1)
            if not p.alive or p._recover_lock.locked():
                self._mark = None
                continue
            if time.monotonic() - p.channel.last_line < p.watchdog_s / 2:  # it speaks: mark its CPU time
                self._mark = _cpu_seconds(p.proc)
            elif time.monotonic() - p.channel.last_line > p.watchdog_s:
                await asyncio.sleep(0.1)  # if our own loop was late, let pending reads land first
                if time.monotonic() - p.channel.last_line > p.watchdog_s and p.alive:
                    silence = _silence(p.name, p.watchdog_s, self._mark, _cpu_seconds(p.proc), p.channel.last_line)
                    await p._recover(*silence, p._generation)

    def take_stalls(self) -> list[str]:
        """The machine's restarts since the last take (a game's: the match records them)."""
        stalls, self.stalls = self.stalls, []
        return stalls


def _silence(
    name: str, watchdog_s: float, mark: Cpu | None, now: Cpu | None, last_line: float
) -> tuple[str, str | None]:
    """(the run's error, the stall or None) of a bot silent past its watchdog, by the CPU time its process got
    from `mark` (taken as it last spoke) to `now`, as a share of one core: under STARVED_SHARE it was starved,
    the machine's fault; else, or unknown, its code blocked it."""
    share = (now[1] - mark[1]) / max(now[0] - mark[0], 1e-3) if now and mark and now[2] == mark[2] else None
    if share is None or share >= STARVED_SHARE:
        return (
            f"Error: the code blocked the bot for more than {watchdog_s:g} s (an endless loop?); the bot was restarted",
            None,
        )
    silent = time.monotonic() - last_line
    return (
        f"Error: the bot was starved of CPU for {silent:.1f} s ({share:.0%} of a core: the machine's fault, not the "
        "code's); the bot was restarted"
    ), f"{name} was starved of CPU for {silent:.1f} s ({share:.0%} of a core) and restarted"


def _cpu_seconds(proc: asyncio.subprocess.Process | None) -> Cpu | None:
    """(monotonic now, the CPU seconds the process has had, user and system, its pid), or None when it cannot
    say."""
    if proc is None or proc.returncode is not None:
        return None
    try:
        times = psutil.Process(proc.pid).cpu_times()
    except psutil.Error:
        return None
    return time.monotonic(), times.user + times.system, proc.pid


def _tick_of(answer: object) -> int | None:
    """The server's tick a run's answer names (the lockstep clock), else None."""
    tick = (answer.get("result") or {}).get("tick") if isinstance(answer, dict) else None
    return tick if isinstance(tick, int) else None
