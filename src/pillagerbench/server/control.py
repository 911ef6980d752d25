"""Client side of the control channel: JSON lines over a socket shared with the server process.

Requests are `{"id", "op", "args"}`; replies `{"id", "ok", "result"|"error"}`; anything with an
`event` key is a pushed event (block dug, item tossed, player joined, ...). The ops are declared in
`js/server/control_ops.json`; the typed methods (`set_block`, `inventory`, ...) come from `Control`.
"""

from __future__ import annotations

import asyncio
import json
from collections.abc import Callable
from typing import Any

from pillagerbench.host.requests import Requests
from pillagerbench.server.seams import Control


class ControlError(RuntimeError):
    """The server refused a control request; the message names the problem."""


class ChannelClosed(ControlError):
    """The control channel closed (the server stopped or died)."""


class ControlChannel(Control):
    def __init__(
        self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter, on_close: Callable[[], str] | None = None
    ):
        self._reader, self._writer = reader, writer
        self._requests = Requests(ControlError)
        self._subscribers: list[asyncio.Queue] = []
        self._on_close = on_close
        self._closed_reason: str | None = None
        self.unmatched: list[dict] = []  # replies to no pending request (e.g. errors for malformed lines)
        self.ready: asyncio.Future = asyncio.get_running_loop().create_future()
        self._task = asyncio.create_task(self._read_loop())

    async def request(self, op: str, timeout: float | None = 30, **args: Any) -> Any:
        if self._closed_reason:
            raise ChannelClosed(self._closed_reason)
        rid = self._requests.next_id()

        async def send() -> None:
            self._writer.write((json.dumps({"id": rid, "op": op, "args": args}) + "\n").encode())
            await self._writer.drain()

        try:
            return await self._requests.ask(rid, send, timeout)
        except asyncio.TimeoutError:
            raise ControlError(f"control op {op!r} got no reply within {timeout} s") from None
        except ConnectionError:
            # The server went away before our read loop noticed; let it record why, then say that.
            await asyncio.wait({self._task}, timeout=2)
            raise ChannelClosed(self._closed_reason or "control channel closed") from None

    @property
    def closed(self) -> bool:
        """The channel has closed (the server ended or the channel failed): no request will be answered."""
        return self._closed_reason is not None

    def subscribe(self) -> asyncio.Queue:
        """A queue receiving every pushed event from now on (dicts with an `event` key)."""
        q: asyncio.Queue = asyncio.Queue()
        self._subscribers.append(q)
        return q

    def unsubscribe(self, q: asyncio.Queue) -> None:
        if q in self._subscribers:
            self._subscribers.remove(q)

    async def _read_loop(self) -> None:
        try:
            while line := await self._reader.readline():
                try:
                    msg = json.loads(line)
                except json.JSONDecodeError:
                    continue
                if "event" in msg:
                    if msg["event"] == "ready" and not self.ready.done():
                        self.ready.set_result(msg)
                    elif msg["event"] == "failed" and not self.ready.done():  # could not start (e.g. port in use)
                        self.ready.set_exception(RuntimeError(str(msg.get("error"))))
                    for q in list(self._subscribers):
                        q.put_nowait(msg)
                    continue
                if not self._requests.answer(msg):
                    self.unmatched = (self.unmatched + [msg])[-20:]
        except (ConnectionError, asyncio.IncompleteReadError):
            pass
        except Exception as exc:  # noqa: BLE001 - e.g. a line over the reader's limit: say so instead of dying silently
            self._failure = f"control channel failed: {type(exc).__name__}: {exc}"
        finally:
            self._closed_reason = (
                getattr(self, "_failure", None)
                or (self._on_close() if self._on_close else None)
                or "control channel closed"
            )
            err = ChannelClosed(self._closed_reason)
            self._requests.fail(err)
            if not self.ready.done():
                self.ready.set_exception(err)
            for q in list(self._subscribers):
                q.put_nowait({"event": "closed", "reason": self._closed_reason})

    async def close(self) -> None:
        try:
            self._writer.close()
        except Exception:  # noqa: BLE001 - closing a transport that may already be gone
            pass
        self._task.cancel()
