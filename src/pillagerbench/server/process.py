"""Start, watch and stop the arena server process (node + flying-squid + our plugins).

    async with ArenaServer() as server:          # free port on 127.0.0.1
        await server.set_block([0, 4, 0], "chest")    # the ops: pillagerbench.server.seams.Control

The server log goes to a file (`log_path`); the control channel is a socket pair inherited by
the child. If the process dies, pending and later requests fail with the exit code and the
last lines of its log.
"""

from __future__ import annotations

import asyncio
import json
import os
import signal
import socket
import tempfile
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pillagerbench.host.node import JS_DIR, node_binary, node_env, profile_args
from pillagerbench.rundir.names import SERVER_LOG
from pillagerbench.server.control import ControlChannel
from pillagerbench.server.seams import Control

LOG = f"{SERVER_LOG}.log"  # the server's log where no path is given (a run directory keeps its own: RunDir)

if TYPE_CHECKING:
    from pillagerbench.config.schema import ServerConfig

MAIN_JS = JS_DIR / "server" / "main.js"
MC_VERSION = "1.16.5"
GROUND_Y = 3  # top of the grass layer; players stand at y = 4
MAX_LINE = 2**28  # a control reply (e.g. a scan of a whole arena) is one JSON line


def exit_code(pid: int) -> int | None:
    """A child's exit code (negative: the signal that ended it) if it has ended, else None, read without
    reaping it: asyncio's child watcher must still collect it, or the process' returncode stays None and
    the server reads as alive after it died (a series then never restarts it)."""
    try:
        info = os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT)
    except ChildProcessError:
        return None
    if info is None:
        return None
    return info.si_status if info.si_code == os.CLD_EXITED else -info.si_status


class ArenaServerError(RuntimeError):
    """The arena server could not start or died."""


class ArenaServer(Control):
    @classmethod
    def from_config(
        cls,
        server_cfg: ServerConfig,
        log_path: str | Path | None = None,
        watch: int | None = None,
        clock: str = "real",
    ) -> ArenaServer:
        """Build from the `server` section of the configuration (and the top-level `watch` port and
        `clock.mode`)."""
        log_dir = server_cfg.log_dir
        return cls(
            host=server_cfg.host,
            port=server_cfg.port,
            log_path=log_path or (Path(log_dir) / LOG if log_dir else None),
            view_distance=server_cfg.view_distance,
            crop_growth_chance=server_cfg.crop_growth_chance,
            tps=int(server_cfg.tps),
            operators=list(server_cfg.operators),
            watch=watch,
            clock=clock,
        )

    def __init__(
        self,
        host: str = "127.0.0.1",
        port: int = 0,
        log_path: str | Path | None = None,
        view_distance: int = 4,
        crop_growth_chance: float = 0.2,
        tps: int = 20,
        operators: list[str] | None = None,
        watch: int | None = None,
        clock: str = "real",
        idle_limit_s: float | None = None,
    ):
        self.host = host
        self.clock_mode = clock  # "real" or "lockstep" (js/server/plugins/lockstep.js)
        self.requested_port = port
        self.port: int | None = None
        self.log_path = Path(log_path) if log_path else Path(tempfile.mkdtemp(prefix="pillagerbench-server-")) / LOG
        self.settings = {
            "host": host,
            "port": port,
            "viewDistance": view_distance,
            "cropGrowthChance": crop_growth_chance,
            "tps": tps,
            "operators": list(operators or []),
            "clock": clock,
        }
        if idle_limit_s is not None:  # how long an idle bot may hold the lockstep clock (plugins/lockstep.js)
            self.settings["idleLimitMs"] = round(idle_limit_s * 1000)
        if watch is not None:  # the live view (js/server/plugins/watch.js) on this port, 0 = a free one
            self.settings["watch"] = {"host": host, "port": int(watch)}
        self.watch_url: str | None = None
        self.process: asyncio.subprocess.Process | None = None
        self.control: ControlChannel | None = None
        self.ready_seconds: float | None = None

    async def start(self, timeout: float = 30) -> ArenaServer:
        self.log_path.parent.mkdir(parents=True, exist_ok=True)
        parent_sock, child_sock = socket.socketpair()
        env = node_env(watch="watch" in self.settings)
        settings = dict(self.settings, controlFd=child_sock.fileno())
        t0 = time.perf_counter()
        with open(self.log_path, "ab") as log:
            self.process = await asyncio.create_subprocess_exec(
                str(node_binary()),
                *profile_args(),
                str(MAIN_JS),
                json.dumps(settings),
                stdin=asyncio.subprocess.DEVNULL,
                stdout=log,
                stderr=asyncio.subprocess.STDOUT,
                pass_fds=(child_sock.fileno(),),
                env=env,
                start_new_session=True,
            )
        child_sock.close()
        reader, writer = await asyncio.open_unix_connection(sock=parent_sock, limit=MAX_LINE)
        self.control = ControlChannel(reader, writer, on_close=self._death_reason)
        try:
            ready = await asyncio.wait_for(asyncio.shield(self.control.ready), timeout)
        except asyncio.TimeoutError:
            await self.stop()
            raise ArenaServerError(
                f"arena server not ready within {timeout} s; log: {self.log_path}\n{self.log_tail()}"
            ) from None
        except Exception as exc:  # noqa: BLE001 - any start failure becomes ArenaServerError
            await self.stop()
            raise ArenaServerError(f"arena server failed to start: {exc}") from None
        self.port = int(ready["port"])
        self.watch_url = ready.get("watch")
        self.ready_seconds = time.perf_counter() - t0
        return self

    def _death_reason(self) -> str:
        code = self.process.returncode if self.process else None
        if code is None and self.process:
            code = exit_code(self.process.pid)
        return f"arena server process ended (exit code {code}); log: {self.log_path}\n{self.log_tail()}"

    def log_tail(self, lines: int = 15) -> str:
        try:
            text = self.log_path.read_text(errors="replace").splitlines()
        except OSError:
            return ""
        return "\n".join(text[-lines:])

    async def request(self, op: str, **args: Any) -> Any:
        if self.control is None:
            raise ArenaServerError("arena server is not started")
        return await self.control.request(op, **args)

    @property
    def alive(self) -> bool:
        """Started, its process not known to have ended and its control channel open (the channel
        closes at once when the process dies; asyncio may learn of the death later)."""
        running = self.process is not None and self.process.returncode is None
        return running and self.control is not None and not self.control.closed

    async def stop(self, timeout: float = 5) -> None:
        proc, self.process = self.process, None
        if self.control:
            await self.control.close()
        if proc is None or proc.returncode is not None:
            return
        try:
            await asyncio.wait_for(proc.wait(), timeout)  # closing the channel asks it to stop
        except asyncio.TimeoutError:
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            await proc.wait()

    async def __aenter__(self) -> ArenaServer:
        return await self.start()

    async def __aexit__(self, *exc) -> None:
        await self.stop()
