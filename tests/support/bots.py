"""Test helper: drive a real mineflayer bot (tests/support/bot_driver.js) from async tests."""

from __future__ import annotations

import asyncio
import itertools
import json
from pathlib import Path

from pillagerbench.host.node import node_binary, node_env

DRIVER = Path(__file__).with_name("bot_driver.js")


class BotError(AssertionError):
    pass


class TestBot:
    __test__ = False  # not a pytest class

    def __init__(self, port: int, username: str, host: str = "127.0.0.1"):
        self.port, self.username, self.host = port, username, host
        self.proc: asyncio.subprocess.Process | None = None
        self.events: list[dict] = []
        self._ids = itertools.count(1)
        self._pending: dict[int, asyncio.Future] = {}
        self._spawned: asyncio.Future | None = None

    async def start(self, timeout: float = 30) -> TestBot:
        loop = asyncio.get_running_loop()
        self._spawned = loop.create_future()
        self.proc = await asyncio.create_subprocess_exec(
            str(node_binary()),
            str(DRIVER),
            json.dumps({"host": self.host, "port": self.port, "username": self.username}),
            stdin=asyncio.subprocess.PIPE,
            stdout=asyncio.subprocess.PIPE,
            stderr=asyncio.subprocess.PIPE,
            env=node_env(),
            limit=2**24,
        )
        self._reader = asyncio.create_task(self._read())
        await asyncio.wait_for(self._spawned, timeout)
        return self

    async def _read(self):
        assert self.proc and self.proc.stdout
        while line := await self.proc.stdout.readline():
            msg = json.loads(line)
            if "event" in msg:
                self.events.append(msg)
                if msg["event"] == "spawned" and not self._spawned.done():
                    self._spawned.set_result(True)
                continue
            fut = self._pending.pop(msg["id"], None)
            if fut and not fut.done():
                fut.set_result(msg)
        err = (await self.proc.stderr.read()).decode(errors="replace")[-2000:] if self.proc.stderr else ""
        exc = BotError(f"bot {self.username} process ended; events={self.events[-3:]} stderr={err}")
        for fut in self._pending.values():
            if not fut.done():
                fut.set_exception(exc)
        if self._spawned and not self._spawned.done():
            self._spawned.set_exception(exc)

    async def eval(self, code: str, timeout: float = 30):
        """Run `code` (body of an async function) in the bot process; return its JSON result."""
        assert self.proc and self.proc.stdin
        rid = next(self._ids)
        fut = asyncio.get_running_loop().create_future()
        self._pending[rid] = fut
        self.proc.stdin.write((json.dumps({"id": rid, "code": code}) + "\n").encode())
        await self.proc.stdin.drain()
        msg = await asyncio.wait_for(fut, timeout)
        if not msg["ok"]:
            raise BotError(f"{self.username}: {msg['error']}")
        return msg["result"]

    @property
    def kicked(self) -> bool:
        return any(e["event"] in ("kicked", "end") for e in self.events)

    async def stop(self):
        if self.proc and self.proc.returncode is None:
            try:
                self.proc.stdin.close()
                await asyncio.wait_for(self.proc.wait(), 3)
            except (asyncio.TimeoutError, BrokenPipeError, ConnectionResetError):
                self.proc.kill()
                await self.proc.wait()

    async def __aenter__(self):
        return await self.start()

    async def __aexit__(self, *exc):
        await self.stop()
