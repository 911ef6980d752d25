"""The channel to one bot process (js/bot/main.js): JSON lines over stdio.

`BotChannel` starts the process under Node's permission model (`bot_command`), reads its stdout
(each message to the player's handler) and stderr (its tail kept, the whole written to the player's
log), sends the declared ops (`bot_protocol.BotOps`) and matches their answers by id, and kills the
process group. What a message means, and when to restart, is the player's (player.py).
"""

from __future__ import annotations

import asyncio
import collections
import contextlib
import json
import os
import signal
import time
from collections.abc import Callable
from pathlib import Path
from typing import IO, Any

from pillagerbench.host.node import JS_DIR, ensure_node_modules, node_binary, node_env, profile_args
from pillagerbench.host.requests import Requests

from .bot_protocol import BotOps, Settings

BOT_MAIN = JS_DIR / "bot" / "main.js"
HEAP_LIMIT_MB = 256


class PlayerError(RuntimeError):
    """The bot process could not start, log in, or answer."""


def bot_command(settings: Settings) -> list[str]:
    """The node command line of a bot process, under Node's permission model."""
    modules = ensure_node_modules(quiet=True)
    profile = profile_args()  # Node writes no profile under its permission model: measuring only
    permission = (
        []
        if profile
        else [
            "--permission",
            f"--allow-fs-read={modules}",
            f"--allow-fs-read={JS_DIR / 'bot'}",
            f"--allow-fs-read={JS_DIR / 'clock'}",
        ]
    )
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


class BotChannel(BotOps):
    """The process of one player's bot and the requests waiting for its answers (the declared ops as
    `BotOps`' typed methods)."""

    def __init__(self, name: str, log_dir: Path | None):
        self.name = name
        self.log_dir = log_dir
        self.proc: asyncio.subprocess.Process | None = None
        self.last_line = 0.0  # monotonic time of the last line on stdout (a heartbeat at least)
        self.expect_exit = False  # the process is ending because we asked it to
        self._requests = Requests(lambda error: PlayerError(f"{name}: {error}"))
        self._stderr_tail: collections.deque[str] = collections.deque(maxlen=40)

    def next_id(self) -> int:
        """A request id not used before (runs and requests share them)."""
        return self._requests.next_id()

    async def spawn(self, settings: Settings) -> asyncio.subprocess.Process:
        self.expect_exit = False
        self.proc = await asyncio.create_subprocess_exec(
            *bot_command(settings),
            stdin=asyncio.subprocess.PIPE,
            stdout=asyncio.subprocess.PIPE,
            stderr=asyncio.subprocess.PIPE,
            env=node_env(),
            start_new_session=True,
            limit=2**26,
        )
        self.last_line = time.monotonic()
        return self.proc

    def stderr_tail(self) -> str:
        return "\n".join(self._stderr_tail)

    def _log_file(self) -> IO[str] | None:
        if not self.log_dir:
            return None
        self.log_dir.mkdir(parents=True, exist_ok=True)
        return open(self.log_dir / f"{self.name}.log", "a", encoding="utf-8")

    async def read_stderr(self, proc: asyncio.subprocess.Process) -> None:
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

    async def read_stdout(self, proc: asyncio.subprocess.Process, on_message: Callable[[dict], None]) -> None:
        """Every JSON line to on_message until stdout ends; returns when the process has exited."""
        assert proc.stdout is not None  # started with stdout=PIPE
        try:
            while True:
                try:
                    line = await proc.stdout.readline()
                except ValueError:  # a line over the limit: skip it
                    continue
                if not line:
                    break
                self.last_line = time.monotonic()
                try:
                    msg = json.loads(line)
                except json.JSONDecodeError:
                    continue
                on_message(msg)
        finally:
            await proc.wait()

    def exit_reason(self, code: int | None) -> str:
        tail = self.stderr_tail()
        if "heap out of memory" in tail or "Reached heap limit" in tail:
            return f"Error: the bot process ran out of memory (heap limit {HEAP_LIMIT_MB} MB) and was restarted"
        if "ERR_ACCESS_DENIED" in tail:
            return "Error: the bot process was denied a resource by the permission model and ended; it was restarted"
        return f"Error: the bot process ended (exit code {code}) and was restarted"

    def answer(self, msg: dict) -> None:
        """An answer to a request: its waiting caller gets the result or a PlayerError."""
        self._requests.answer(msg)

    def fail_pending(self, reason: str) -> None:
        """Every request still waiting ends with a PlayerError saying `reason`."""
        self._requests.fail(PlayerError(f"{self.name}: {reason}"))

    async def send(self, msg: dict) -> None:
        if not self.proc or self.proc.returncode is not None or not self.proc.stdin:
            raise PlayerError(f"{self.name}: bot process is not running")
        self.proc.stdin.write((json.dumps(msg) + "\n").encode())
        try:
            await self.proc.stdin.drain()
        except (ConnectionResetError, BrokenPipeError) as exc:
            raise PlayerError(f"{self.name}: bot process is not running ({exc})") from None

    async def cue(self) -> None:
        """Tell the bot, launched with `"cue": true`, to log in now (the `login` op). A process that has
        ended already is no error here: its reader says why."""
        with contextlib.suppress(PlayerError):
            await self.login()

    async def _exchange(self, rid: int, line: dict, wait: float) -> Any:
        """Send request `line` (its id `rid`); wait up to `wait` seconds for its answer (the JSON value
        js/bot/main.js's op returns)."""
        try:
            return await self._requests.ask(rid, lambda: self.send(line), wait)
        except asyncio.TimeoutError:
            raise PlayerError(f"{self.name}: no answer to {line['op']!r} within {wait} s") from None

    async def kill(self) -> None:
        proc = self.proc
        if proc is None or proc.returncode is not None:
            return
        self.expect_exit = True
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        await proc.wait()

    async def close(self) -> None:
        """Close stdin and give the process 2 s to end; kill it if it does not."""
        proc = self.proc
        if proc is None or proc.returncode is not None:
            return
        self.expect_exit = True
        try:
            if proc.stdin is not None:
                proc.stdin.close()
            await asyncio.wait_for(proc.wait(), 2)
        except (asyncio.TimeoutError, BrokenPipeError, ConnectionResetError):
            await self.kill()
