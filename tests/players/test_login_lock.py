"""One login at a time per server (players/bot_process.py): two bots logging in to one server share a
lock, and the lock is gone once no login holds or awaits it, so a long run's servers (a league's
round each) and closed event loops leave nothing behind (docs/performance.md, the league's hour)."""

from __future__ import annotations

import asyncio
import gc
from types import SimpleNamespace

from pillagerbench.players import bot_process
from pillagerbench.players.bot_process import BotProcess


def _bot(port: int) -> SimpleNamespace:
    return SimpleNamespace(host="127.0.0.1", server_port=port)


def test_logins_to_one_server_take_turns_and_leave_no_lock_behind():
    order: list[str] = []

    async def login(name: str, port: int) -> None:
        async with BotProcess._login_lock(_bot(port)):  # type: ignore[arg-type]
            order.append(f"{name} in")
            await asyncio.sleep(0.01)
            order.append(f"{name} out")

    async def three() -> None:
        await asyncio.gather(login("a", 1), login("b", 1), login("c", 2))

    for _ in range(3):  # a round each: a fresh event loop and a server on a fresh port
        order.clear()
        asyncio.run(three())
        one_server = [e for e in order if e[0] in "ab"]
        assert one_server in (["a in", "a out", "b in", "b out"], ["b in", "b out", "a in", "a out"])
        assert order.index("c in") < order.index("a out")  # another server's login does not wait
    gc.collect()
    assert dict(bot_process._login_locks) == {}
