"""One player's bot process through its life (a Node process, mineflayer; players/player.py is the player's
API over it): launched with its settings, cued to log in (one login at a time per server), its lines
read and dispatched (heartbeats, the events and the answer of the run under way, the spawn, a fatal
error), watched, and restarted when it dies or stays silent.

The process speaks JSON lines over stdio, declared in js/bot/bot_protocol.json (bot_protocol.py: the
typed ops and settings; channel.py holds the process and its requests, placement.py sets and restores
inventory and position). It writes a heartbeat every 200 ms; when it stays silent for `watchdog_s`
(agent code blocking its event loop), or dies, its process group is killed, it logs in again with the
same name, its inventory and position are restored through the control channel (when `server` is
given) and the run under way ends with an onError event.

A silent bot is told apart by the CPU time its process got while silent (from the watchdog's last look
while it spoke, which comes after its last heartbeat, to the verdict): a loop in its code burns a core
(its fair share of one, on a busy machine); a bot stopped or starved by the machine got next to none
(under `STARVED_SHARE` of a core), and that restart is ours, not the code's: `Watchdog` keeps it in its
`stalls` with a bot that did not stop within 2 s, and the match records them (the episode is spoiled).
"""

from __future__ import annotations

import asyncio
import time
import weakref
from collections.abc import Callable
from pathlib import Path

import psutil

from pillagerbench.server.seams import Control

from . import placement
from .bot_protocol import Settings
from .channel import BotChannel, PlayerError
from .observation import Observation, observation

# One login at a time per server (flying-squid handles concurrent logins badly), with a short gap. A lock
# lives while a login holds or awaits it (a weak table: a long run's servers and loops leave none behind).
_login_locks: weakref.WeakValueDictionary[tuple[str, int], asyncio.Lock] = weakref.WeakValueDictionary()
LOGIN_GAP_S = 0.05
# A bot silent past its watchdog whose process got less than this share of one core meanwhile was
# starved (stopped, or the machine gave it no time), not looping: a loop burns its fair share of a core
# (all of one on a calm machine; 0.28 to 0.41 on 2 cores beside 4 CPU-bound processes, docs/performance.md),
# a stopped bot none. A tenth: a loop still gets it beside 19 busy processes on 2 cores.
STARVED_SHARE = 0.1
Cpu = tuple[float, float, int]  # a process's CPU time read: (monotonic then, its CPU seconds, its pid)


class PendingRun:
    """The run under way: its events as they come (each also to `on_event`), and its answer (`done`)."""

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


class BotProcess:
    """One player's bot process: the current one (a restart starts a new one), watched and restarted."""

    def __init__(
        self,
        name: str,
        server_port: int,
        *,
        host: str,
        log_dir: Path | None,
        primitives: list[str] | None,
        server: Control | None,
        watchdog_s: float,
        login_timeout: float,
        clock: str,
        view: bool = False,
    ):
        self.name, self.server_port, self.host = name, server_port, host
        self.clock = clock  # "real" or "lockstep": the bot's timers on the wall clock or the server's ticks
        self.view = view  # a person's player: its bot can serve the first-person view (js/bot/view.js)
        self.primitives = primitives
        self.server = server  # the arena's control channel, to restore a restarted bot (None: not restored)
        self.watchdog_s = watchdog_s
        self.login_timeout = login_timeout
        self.restarts = 0
        self.watchdog = Watchdog(self)  # its silence judged: the code's or the machine's (a stall)
        self.channel = BotChannel(name, log_dir)
        self.pending: PendingRun | None = None  # the run under way: its events and answer go to it
        self.closed = False
        self.generation = 0  # the process's launch count: what a dead process's reader or a late verdict names
        self.position: list[float | None] | None = None
        self._recover_lock = asyncio.Lock()
        self._spawned: asyncio.Future | None = None
        self._awaits_cue = False  # a process is launched and not yet cued to log in
        self._tasks: list[asyncio.Task] = []
        self._recoveries: set[asyncio.Task] = set()  # held so a running recovery is not garbage-collected
        self._fatal: str | None = None
        self._last_obs: Observation = {}  # the last seen: a restart restores from it when the server cannot say

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

    @property
    def restarting(self) -> bool:
        return self._recover_lock.locked()

    def _login_lock(self) -> asyncio.Lock:
        return _login_locks.setdefault((self.host, self.server_port), asyncio.Lock())

    async def start(self) -> None:
        """Spawn the bot process (unless `launch` has), log in and wait until it has spawned."""
        if not self._awaits_cue:
            await self.launch()
        async with self._login_lock():
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
        self.generation += 1
        self._spawned = loop.create_future()
        self._fatal = None
        proc = await self.channel.spawn(settings)
        self._awaits_cue = True
        gen = self.generation
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
            if gen == self.generation and not self.channel.expect_exit and not self.closed:
                reason = self._fatal or self.channel.exit_reason(proc.returncode)
                if self._spawned and not self._spawned.done():
                    self._spawned.set_exception(
                        PlayerError(f"{self.name}: bot process ended before spawning: {reason}")
                    )
                else:
                    task = asyncio.create_task(self.restart(reason, None, gen))
                    self._recoveries.add(task)
                    task.add_done_callback(self._recoveries.discard)

    def _dispatch(self, msg: dict) -> None:
        if "hb" in msg:
            return
        if "ev" in msg:
            run = self.pending
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
        run = self.pending
        if run is not None and msg.get("id") == run.rid:
            if not run.done.done():
                run.done.set_result(msg)
            return
        self.channel.answer(msg)

    async def observe(self) -> Observation:
        """The bot's observation now (the `observe` request), kept as the last one seen."""
        self._last_obs = observation(await self.channel.observe())
        return self._last_obs

    async def restart(self, reason: str, stall: str | None, gen: int) -> None:
        """Kill (if needed), log in again, restore state, and end the pending run with onError. `stall`: the
        restart is the machine's fault (the watchdog keeps it for the match). `gen`: the process it is
        for; a later one is left alone."""
        async with self._recover_lock:
            if gen != self.generation or self.closed:
                return
            self.watchdog.stalls += [stall] if stall else []
            saved = await placement.snapshot(self.server, self.name, self._last_obs)
            await self.channel.kill()
            self.channel.fail_pending(reason)
            self.restarts += 1
            obs: Observation = {}
            try:
                await self.relogin()
                await placement.restore(self.server, self.channel, self.name, saved)
                obs = await self.observe()
            except Exception as exc:  # noqa: BLE001 - report it in the run's events
                reason = f"{reason}; restarting failed: {exc}"
            run = self.pending
            if run is not None and not run.done.done():
                run.add(["onError", {**obs, "onError": reason}])
                run.add(["observe", obs])
                run.done.set_result({"id": run.rid, "ok": True, "recovered": True})

    async def restarted(self) -> None:
        """Once a restart under way has ended (at once when none is)."""
        if self._recover_lock.locked():
            async with self._recover_lock:
                pass

    async def relogin(self) -> None:
        """A new process, logged in with the same name (a few tries)."""
        last: Exception | None = None
        for attempt in range(5):
            try:
                async with self._login_lock():
                    await self.launch()
                    await self._login()
                return
            except PlayerError as exc:
                last = exc
                await asyncio.sleep(0.3 * (attempt + 1))
        raise PlayerError(f"{self.name}: could not log in again: {last}")

    async def close(self) -> None:
        self.closed = True
        await self.channel.close()
        for t in self._tasks:
            if not t.done():
                t.cancel()
        self._tasks.clear()


class Watchdog:
    """Python's watchdog of one bot, which writes a heartbeat every 200 ms: silent for its `watchdog_s`,
    the bot is restarted, its silence put on its code (an endless loop) or, when its process got under
    STARVED_SHARE of a core meanwhile, on the machine. The machine's restarts (those, and a bot that did
    not stop in time) are `stalls`, kept until the match takes them (`take_stalls`)."""

    def __init__(self, bot: BotProcess):
        self.bot = bot
        self.stalls: list[str] = []
        self._mark: Cpu | None = None  # the bot's process as it last spoke

    async def run(self) -> None:
        b = self.bot
        while not b.closed:
            await asyncio.sleep(0.1)
            if not b.alive or b.restarting:
                self._mark = None
                continue
            if time.monotonic() - b.channel.last_line < b.watchdog_s / 2:  # it speaks: mark its CPU time
                self._mark = _cpu_seconds(b.proc)
            elif time.monotonic() - b.channel.last_line > b.watchdog_s:
                await asyncio.sleep(0.1)  # if our own loop was late, let pending reads land first
                if time.monotonic() - b.channel.last_line > b.watchdog_s and b.alive:
                    silence = _silence(b.name, b.watchdog_s, self._mark, _cpu_seconds(b.proc), b.channel.last_line)
                    await b.restart(*silence, b.generation)

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
