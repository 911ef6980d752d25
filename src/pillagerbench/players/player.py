"""The Python handle of one player: a bot process (Node, mineflayer) that runs agent code.

    async with ArenaServer() as server:
        player = Player("Ryn", server.port, server=server)
        await player.start()
        await player.reset(position=(-7, 4, -10), inventory={"bread": 2})
        events = await player.run("await mineBlock(bot, 'slime_block', 2)")
        assert events[-1][0] == "observe"
        await player.close()

The bot process speaks JSON lines over stdio (see js/bot/main.js). It writes a heartbeat every
200 ms; when it stays silent for `watchdog_s` (agent code blocking its event loop), or dies, the
handle kills its process group, logs in again with the same name, restores inventory and position
through the control channel (when `server` is given) and ends the pending run with an onError event.
"""

from __future__ import annotations

import asyncio
import collections
import itertools
import json
import os
import signal
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from pillagerbench.control import Control
from pillagerbench.node import JS_DIR, ensure_node_modules, node_binary, node_env, profile_args

BOT_MAIN = JS_DIR / "bot" / "main.js"
HEAP_LIMIT_MB = 256

# One login at a time per server (flying-squid handles concurrent logins badly), with a short gap.
_login_locks: dict[tuple[str, int], asyncio.Lock] = {}
LOGIN_GAP_S = 0.05


class PlayerError(RuntimeError):
    """The bot process could not start, log in, or answer."""


def bot_command(settings: dict[str, Any]) -> list[str]:
    """The node command line of a bot process, under Node's permission model."""
    modules = ensure_node_modules(quiet=True)
    profile = profile_args()  # Node writes no profile under its permission model: measuring only
    permission = [] if profile else ["--permission", f"--allow-fs-read={modules}", f"--allow-fs-read={JS_DIR / 'bot'}"]
    return [
        str(node_binary()),
        *permission,
        f"--max-old-space-size={HEAP_LIMIT_MB}",
        "--stack-size=2000",
        "--max-semi-space-size=4",  # a small young generation: ~25 MB less RSS per bot
        *profile,
        str(BOT_MAIN),
        json.dumps(settings),
    ]


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
    ):
        self.name = name
        self.server_port = server_port
        self.host = host
        self.log_dir = Path(log_dir) if log_dir else None
        self.primitives = list(primitives) if primitives is not None else None
        self.server = server  # the arena's control channel (None: no server-side checks)
        self.watchdog_s = watchdog_s
        self.login_timeout = login_timeout
        self.restarts = 0
        self.proc: asyncio.subprocess.Process | None = None
        self._ids = itertools.count(1)
        self._pending: dict[int, asyncio.Future] = {}
        self._run: _RunState | None = None
        self._run_lock = asyncio.Lock()
        self._recover_lock = asyncio.Lock()
        self._last_line = 0.0
        self._spawned: asyncio.Future | None = None
        self._tasks: list[asyncio.Task] = []
        self._recoveries: set[asyncio.Task] = set()  # held so a running recovery is not garbage-collected
        self._stderr_tail: collections.deque[str] = collections.deque(maxlen=40)
        self._fatal: str | None = None
        self._expect_exit = False
        self._closed = False
        self._generation = 0
        self.position: list[float | None] | None = None
        self._last_obs: dict = {}

    # ---- process ----------------------------------------------------------------------------
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
        """Spawn the bot process, log in and wait until it has spawned."""
        key = (self.host, self.server_port)
        lock = _login_locks.setdefault(key, asyncio.Lock())
        async with lock:
            await self._spawn()
            await asyncio.sleep(LOGIN_GAP_S)

    async def _spawn(self) -> None:
        settings = {
            "host": self.host,
            "port": self.server_port,
            "username": self.name,
            "primitives": self.primitives,
            "heartbeatMs": 200,
        }
        loop = asyncio.get_running_loop()
        self._generation += 1
        self._spawned = loop.create_future()
        self._fatal = None
        self._expect_exit = False
        self.proc = await asyncio.create_subprocess_exec(
            *bot_command(settings),
            stdin=asyncio.subprocess.PIPE,
            stdout=asyncio.subprocess.PIPE,
            stderr=asyncio.subprocess.PIPE,
            env=node_env(),
            start_new_session=True,
            limit=2**26,
        )
        self._last_line = time.monotonic()
        gen = self._generation
        self._tasks = [t for t in self._tasks if not t.done()]
        self._tasks.append(asyncio.create_task(self._read_stdout(self.proc, gen)))
        self._tasks.append(asyncio.create_task(self._read_stderr(self.proc)))
        if not any(t.get_name() == f"watchdog-{self.name}" and not t.done() for t in self._tasks):
            self._tasks.append(asyncio.create_task(self._watchdog(), name=f"watchdog-{self.name}"))
        try:
            await asyncio.wait_for(asyncio.shield(self._spawned), self.login_timeout)
        except asyncio.TimeoutError:
            await self._kill()
            raise PlayerError(
                f"{self.name}: bot did not spawn within {self.login_timeout} s\n{self.stderr_tail()}"
            ) from None
        except PlayerError:
            await self._kill()
            raise

    def stderr_tail(self) -> str:
        return "\n".join(self._stderr_tail)

    def _log_file(self):
        if not self.log_dir:
            return None
        self.log_dir.mkdir(parents=True, exist_ok=True)
        return open(self.log_dir / f"{self.name}.log", "a", encoding="utf-8")

    async def _read_stderr(self, proc: asyncio.subprocess.Process) -> None:
        log = self._log_file()
        assert proc.stderr is not None  # started with stderr=PIPE
        try:
            while line := await proc.stderr.readline():
                text = line.decode(errors="replace").rstrip()
                self._stderr_tail.append(text)
                if log:
                    log.write(text + "\n")
                    log.flush()
        finally:
            if log:
                log.close()

    async def _read_stdout(self, proc: asyncio.subprocess.Process, gen: int) -> None:
        assert proc.stdout is not None  # started with stdout=PIPE
        try:
            while True:
                try:
                    line = await proc.stdout.readline()
                except ValueError:  # a line over the limit: skip it
                    continue
                if not line:
                    break
                self._last_line = time.monotonic()
                try:
                    msg = json.loads(line)
                except json.JSONDecodeError:
                    continue
                self._dispatch(msg)
        finally:
            await proc.wait()
            if gen == self._generation and not self._expect_exit and not self._closed:
                reason = self._fatal or self._exit_reason(proc.returncode)
                if self._spawned and not self._spawned.done():
                    self._spawned.set_exception(
                        PlayerError(f"{self.name}: bot process ended before spawning: {reason}")
                    )
                else:
                    task = asyncio.create_task(self._recover(reason, gen))
                    self._recoveries.add(task)
                    task.add_done_callback(self._recoveries.discard)

    def _exit_reason(self, code: int | None) -> str:
        tail = self.stderr_tail()
        if "heap out of memory" in tail or "Reached heap limit" in tail:
            return f"Error: the bot process ran out of memory (heap limit {HEAP_LIMIT_MB} MB) and was restarted"
        if "ERR_ACCESS_DENIED" in tail:
            return "Error: the bot process was denied a resource by the permission model and ended; it was restarted"
        return f"Error: the bot process ended (exit code {code}) and was restarted"

    def _dispatch(self, msg: dict) -> None:
        if "hb" in msg:
            return
        if "ev" in msg:
            run = self._run
            if isinstance(msg["ev"], list) and len(msg["ev"]) == 2 and isinstance(msg["ev"][1], dict):
                self._last_obs = msg["ev"][1]
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
        rid: Any = msg.get("id")
        run = self._run
        if run is not None and rid == run.rid:
            if not run.done.done():
                run.done.set_result(msg)
            return
        fut = self._pending.pop(rid, None)
        result = msg.get("result")
        if isinstance(result, dict) and "status" in result and "inventory" in result:
            self._last_obs = result
        if fut is not None and not fut.done():
            if msg.get("ok"):
                fut.set_result(msg.get("result"))
            else:
                fut.set_exception(PlayerError(f"{self.name}: {msg.get('error')}"))

    async def _send(self, msg: dict) -> None:
        if not self.proc or self.proc.returncode is not None or not self.proc.stdin:
            raise PlayerError(f"{self.name}: bot process is not running")
        self.proc.stdin.write((json.dumps(msg) + "\n").encode())
        try:
            await self.proc.stdin.drain()
        except (ConnectionResetError, BrokenPipeError) as exc:
            raise PlayerError(f"{self.name}: bot process is not running ({exc})") from None

    async def _request(self, op: str, wait: float = 10.0, **args: Any) -> Any:
        """Send request `op` with `args`; wait up to `wait` seconds for the answer."""
        timeout = wait
        rid = next(self._ids)
        fut = asyncio.get_running_loop().create_future()
        self._pending[rid] = fut
        try:
            await self._send({"id": rid, "op": op, **args})
            return await asyncio.wait_for(fut, timeout)
        except asyncio.TimeoutError:
            raise PlayerError(f"{self.name}: no answer to {op!r} within {timeout} s") from None
        finally:
            self._pending.pop(rid, None)

    async def _kill(self) -> None:
        proc = self.proc
        if proc is None or proc.returncode is not None:
            return
        self._expect_exit = True
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        await proc.wait()

    # ---- watchdog and recovery -------------------------------------------------------------
    async def _watchdog(self) -> None:
        while not self._closed:
            await asyncio.sleep(0.1)
            if not self.alive or self._recover_lock.locked():
                continue
            if time.monotonic() - self._last_line > self.watchdog_s:
                await asyncio.sleep(0.1)  # if our own loop was late, let pending reads land first
                if time.monotonic() - self._last_line > self.watchdog_s and self.alive:
                    await self._recover(
                        f"Error: the code blocked the bot for more than {self.watchdog_s:g} s "
                        "(an endless loop?); the bot was restarted",
                        self._generation,
                    )

    async def _recover(self, reason: str, gen: int) -> None:
        """Kill (if needed), log in again, restore state, and end the pending run with onError."""
        async with self._recover_lock:
            if gen != self._generation or self._closed:
                return
            snapshot = await self._snapshot()
            await self._kill()
            for fut in self._pending.values():
                if not fut.done():
                    fut.set_exception(PlayerError(f"{self.name}: {reason}"))
            self._pending.clear()
            self.restarts += 1
            obs: dict = {}
            try:
                await self._relogin()
                await self._restore(snapshot)
                obs = await self._request("observe")
            except Exception as exc:  # noqa: BLE001 - report it in the run's events
                reason = f"{reason}; restarting failed: {exc}"
            run = self._run
            if run is not None and not run.done.done():
                run.add(["onError", {**obs, "onError": reason}])
                run.add(["observe", obs])
                run.done.set_result({"id": run.rid, "ok": True, "recovered": True})

    async def _snapshot(self) -> dict | None:
        """Inventory and position to restore: from the server while the player is still connected,
        else from the last observation seen."""
        if self.server is None:
            return None
        try:
            players = await asyncio.wait_for(self.server.players(), 2)
            pos = next((p["pos"] for p in players if p["name"] == self.name), None)
            if pos is not None:
                inv = await asyncio.wait_for(self.server.inventory(self.name), 2)
                items: dict[str, int] = {}
                for slot in inv:
                    items[slot["name"]] = items.get(slot["name"], 0) + slot["count"]
                return {"items": items, "pos": pos}
        except Exception:  # noqa: BLE001 - fall back to the last observation
            pass
        obs = self._last_obs
        if not obs:
            return None
        p = (obs.get("status") or {}).get("position")
        return {"items": dict(obs.get("inventory") or {}), "pos": [p["x"], p["y"], p["z"]] if p else None}

    async def _relogin(self) -> None:
        last: Exception | None = None
        for attempt in range(5):
            try:
                lock = _login_locks.setdefault((self.host, self.server_port), asyncio.Lock())
                async with lock:
                    await self._spawn()
                return
            except PlayerError as exc:
                last = exc
                await asyncio.sleep(0.3 * (attempt + 1))
        raise PlayerError(f"{self.name}: could not log in again: {last}")

    async def _restore(self, snapshot: dict | None) -> None:
        if not snapshot or self.server is None:
            return
        await self.server.set_inventory(self.name, snapshot["items"])
        if snapshot["pos"]:
            await self._teleport(snapshot["pos"])

    def _control(self) -> Control:
        if self.server is None:
            raise PlayerError(f"{self.name}: this needs `server=` (the arena's control channel)")
        return self.server

    async def _teleport(self, pos: list[float]) -> None:
        for _attempt in range(3):
            await self._control().teleport(self.name, pos)
            settled = await self._request("settle", pos=pos, timeout=3, wait=6)
            if settled is True:
                return
        raise PlayerError(f"{self.name}: teleport to {pos} did not arrive (bot at {settled})")

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
            rid = next(self._ids)
            state = _RunState(rid, on_event)
            self._run = state
            try:
                msg: dict = {"id": rid, "op": "run", "code": code}
                if timeout:
                    msg["timeout"] = timeout
                try:
                    await self._send(msg)
                except PlayerError as exc:
                    state.add(["onError", {"onError": str(exc)}])
                    return state.events
                await state.done
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
            await self._send({"id": next(self._ids), "op": "stop"})
        except PlayerError:
            return
        try:
            await asyncio.wait_for(asyncio.shield(run.done), 2.0)
        except asyncio.TimeoutError:
            await self._recover("Error: the bot did not stop within 2 s and was restarted", self._generation)

    async def observe(self) -> list:
        return [["observe", await self._request("observe")]]

    async def lag(self, *, reset: bool = False) -> dict:
        """How late this bot's 50 ms physics ticks were since the last `lag(reset=True)`, measured in
        the bot process (js/bot/lag.js): ticks, wall_s, tick_rate, late_mean_ms, late_max_ms, late_pct."""
        return await self._request("lag", reset=reset)

    async def reset(
        self,
        *,
        position: Sequence[float] | None = None,
        inventory: dict[str, int] | None = None,
        equipment: Sequence[str | None] | dict | None = None,
    ) -> list:
        """Stop code, then set inventory/equipment/position (through the control channel) and return
        [["observe", {...}]]. Events from before the reset are dropped."""
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
                items = dict(inventory or {})
                for name in _equipment_names(equipment):
                    if name not in (inventory or {}):  # equipment not listed in the inventory is extra
                        items[name] = items.get(name, 0) + 1
                await self._control().set_inventory(self.name, items)
            if position is not None:
                await self._teleport(_centred(position))
            if equipment is not None:
                await self._wait_inventory(inventory or {}, equipment)
                await self._request("equip", equipment=equipment, wait=15)
            await self._request("clear")
            return await self.observe()

    async def _wait_inventory(self, inventory: dict[str, int], equipment) -> None:
        want = dict(inventory)
        for name in _equipment_names(equipment):
            want.setdefault(name, 1)
        for _ in range(100):
            inv = (await self._request("observe"))["inventory"]
            if all(inv.get(k, 0) >= v for k, v in want.items()):
                return
            await asyncio.sleep(0.02)

    async def close(self) -> None:
        self._closed = True
        if self._run is not None:
            await self.stop()
        proc = self.proc
        if proc is not None and proc.returncode is None:
            self._expect_exit = True
            try:
                if proc.stdin is not None:
                    proc.stdin.close()
                await asyncio.wait_for(proc.wait(), 2)
            except (asyncio.TimeoutError, BrokenPipeError, ConnectionResetError):
                await self._kill()
        for t in self._tasks:
            if not t.done():
                t.cancel()
        self._tasks.clear()

    async def __aenter__(self) -> Player:
        await self.start()
        return self

    async def __aexit__(self, *exc) -> None:
        await self.close()


def _centred(position: Sequence[float]) -> list[float]:
    """Whole-number x/z mean the middle of that block (as Minecraft's /tp does)."""
    x, y, z = (float(v) for v in position)
    return [x + 0.5 if x.is_integer() else x, y, z + 0.5 if z.is_integer() else z]


def _equipment_names(equipment) -> list[str]:
    if equipment is None:
        return []
    if isinstance(equipment, dict):
        return [v for v in equipment.values() if v]
    return [v for v in equipment if v]
