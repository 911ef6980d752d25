"""Recorder.stop() ends even when the frame loop never sees its cancel.

On Python 3.11 `asyncio.wait_for` (under every control request) returns the reply instead of
raising CancelledError when the cancel and the reply land in the same loop iteration (CPython
gh-86296). A fidelity run hung for 18 minutes at a whistle that way: the recorder's loop swallowed
the cancel and `stop()` waited for it forever. The fake control channel below is real
`asyncio.wait_for` on a reply future, and the test lands the reply and the stop together."""

from __future__ import annotations

import asyncio

from pillagerbench.replay.record import Recorder
from pillagerbench.server.seams import Control

FRAME = {"tick": 1, "players": [], "blocks": [], "items": [], "mobs": []}


class _Channel(Control):
    """Answers `replay_frame` only when the test says so (`answer()`), through asyncio.wait_for."""

    def __init__(self):
        self.waiting: asyncio.Future | None = None
        self.asked = asyncio.Event()
        self.requests = 0

    async def request(self, op, timeout=30, **args):
        self.requests += 1
        if args.get("start") or args.get("stop"):
            return FRAME
        self.waiting = asyncio.get_running_loop().create_future()
        self.asked.set()
        return await asyncio.wait_for(self.waiting, timeout)

    def answer(self):
        self.asked.clear()
        self.waiting.set_result(FRAME)

    def subscribe(self):
        return asyncio.Queue()

    def unsubscribe(self, q):
        pass


class _Server:
    def __init__(self):
        self.control = _Channel()


def test_stop_ends_the_recording_when_a_frame_reply_swallows_the_cancel(tmp_path):
    async def main():
        server = _Server()
        recorder = Recorder(server, tmp_path / "replay.jsonl.gz", {"scenario": "x"})
        await recorder.start()
        await asyncio.wait_for(server.control.asked.wait(), 2)  # the loop waits for a frame's reply
        server.control.answer()  # the reply lands ...
        stopping = asyncio.ensure_future(recorder.stop({"red": 1}))  # ... and the stop, in one iteration
        done, _ = await asyncio.wait({stopping}, timeout=5)
        assert done, "Recorder.stop() did not return within 5 s"
        await asyncio.sleep(0.5)
        asked = server.control.requests
        await asyncio.sleep(0.5)
        assert server.control.requests == asked, "the frame loop still runs after stop()"

    asyncio.run(main())
