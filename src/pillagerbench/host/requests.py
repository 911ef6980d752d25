"""The request/reply machine of a JSON-lines channel, one for every channel (the arena server's control
channel, a bot's stdio): ids, the requests waiting for their answers, each answer matched to its request by
id (`ok` with a `result`, or an `error`), and every one still waiting failed at once when the channel ends.
What a channel sends and how it names its errors are its own."""

from __future__ import annotations

import asyncio
import itertools
from collections.abc import Awaitable, Callable
from typing import Any


class Requests:
    """Requests in flight; `refused(text)` is the exception an `ok: false` answer raises in its caller."""

    def __init__(self, refused: Callable[[str], Exception]):
        self._ids = itertools.count(1)
        self._waiting: dict[Any, asyncio.Future] = {}
        self.refused = refused

    def next_id(self) -> int:
        """An id not used before on this channel."""
        return next(self._ids)

    async def ask(self, rid: int, send: Callable[[], Awaitable[None]], timeout: float | None) -> Any:
        """Send a request (`send()`, its id `rid`) and wait up to `timeout` seconds for its answer's result
        (asyncio.TimeoutError past it, for the channel to say in its own words)."""
        fut = asyncio.get_running_loop().create_future()
        self._waiting[rid] = fut
        try:
            await send()
            return await asyncio.wait_for(fut, timeout)
        finally:
            self._waiting.pop(rid, None)

    def answer(self, msg: dict) -> bool:
        """An answer to its waiting request: its result, or `refused`; False when nothing waits for it."""
        fut = self._waiting.pop(msg.get("id"), None)
        if fut is None or fut.done():
            return False
        if msg.get("ok"):
            fut.set_result(msg.get("result"))
        else:
            fut.set_exception(self.refused(str(msg.get("error", "unknown error"))))
        return True

    def fail(self, exc: Exception) -> None:
        """Every request still waiting ends with `exc` (the channel ended)."""
        for fut in self._waiting.values():
            if not fut.done():
                fut.set_exception(exc)
        self._waiting.clear()
