"""Record an episode from the server's own state through the control channel.

    recorder = Recorder(server, episode_dir / RECORDING, header)
    await recorder.start()          # the arena's blocks, then a frame every 1/FRAME_HZ s
    recorder.score(t, {"red": 3, "blue": 1}); recorder.program("Raze", "start")
    await recorder.stop(final_scores)

The file is gzip JSON lines (docs/replays.md): a header, the arena's blocks, then records with a
time `t` (seconds since the game started). It is flushed every FLUSH_S seconds, so a run killed
mid-episode leaves a recording that plays up to where it ends. A recording never fails the
episode: if the server stops answering, the recording ends there.
"""

from __future__ import annotations

import asyncio
import gzip
import json
import time
from pathlib import Path
from typing import Any

from pillagerbench.rundir.names import REPLAY
from pillagerbench.server.clock import CLOCK_EVENT, GameClock, RealClock

RECORDING = REPLAY  # the recording in an episode directory (rundir/names.py)
FORMAT = "pillagerbench-replay"
VERSION = 1
FRAME_HZ = 5
FLUSH_S = 2.0
STOP_WAIT_S = 2.0  # stop() waits at most this long for the frame loop to end
GROUND_Y = 3  # the flat world's grass layer: the lowest layer a top-down map needs


class Recorder:
    def __init__(
        self, server, path: Path, header: dict[str, Any], box: tuple | None = None, clock: GameClock | None = None
    ):
        self.server, self.path, self.box = server, Path(path), box
        self.clock = clock or RealClock()  # frames and their times in game time (config `clock`)
        self.header = {"type": "header", "format": FORMAT, "version": VERSION, "frame_hz": FRAME_HZ, **header}
        self._file: gzip.GzipFile | None = None
        self._task: asyncio.Task | None = None
        self._start = 0.0
        self._last_flush = 0.0
        self._items: dict[int, list] = {}
        self._mobs: dict[int, list] = {}
        self._picked: dict[int, str] = {}  # item entity id -> player who picked it up
        self._events: asyncio.Queue | None = None
        self._runs: dict[str, int] = {}
        self.frames = 0
        self.error: str | None = None
        self._stopping = False

    # ---- writing ----
    def _write(self, record: dict) -> None:
        if self._file is None:
            return
        self._file.write((json.dumps(record, separators=(",", ":")) + "\n").encode())
        now = time.monotonic()
        if now - self._last_flush >= FLUSH_S:
            self._file.flush()  # a sync flush: everything so far can be read even if the run is killed
            self._last_flush = now

    def now(self) -> float:
        return round(self.clock.now() - self._start, 2)

    # ---- life cycle ----
    async def start(self) -> None:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._file = gzip.GzipFile(self.path, "wb", compresslevel=6)
        self._write({**self.header, "started": round(time.time(), 3)})
        if self.box:
            (x0, _, z0), (x1, y1, z1) = self.box
            blocks = await self.server.control.scan([x0, GROUND_Y, z0], [x1, y1, z1])
            palette: dict[str, int] = {}
            rows = [[x, y, z, palette.setdefault(name, len(palette))] for x, y, z, name, *_ in blocks]
            self._write(
                {"type": "blocks", "box": [[x0, GROUND_Y, z0], [x1, y1, z1]], "palette": list(palette), "blocks": rows}
            )
        self._events = self.server.control.subscribe()
        self._start = self.clock.now()
        self._last_flush = time.monotonic()
        await self._frame(start=True)
        self._task = asyncio.create_task(self._loop(), name="replay-recorder")

    async def _loop(self) -> None:
        period = 1.0 / FRAME_HZ
        k = 1
        # A flag as well as cancel(): on Python 3.11 asyncio.wait_for (under every control request)
        # swallows a cancel that lands as its reply does (CPython gh-86296), and the loop would run on.
        try:
            while not self._stopping:
                due = self._start + k * period
                async with self.clock.at(due, "replay"):  # lockstep: that tick exactly, the world held
                    await self._frame()
                    now = self.clock.now()  # read while held: on the lockstep clock never late
                k = max(k + 1, int((now - self._start) / period) + 1)  # late: skip, never bunch up
        except asyncio.CancelledError:
            raise
        except Exception as exc:  # noqa: BLE001 - the recording ends; the episode goes on
            self.error = f"{type(exc).__name__}: {exc}"
        finally:
            await self.clock.let_go("replay")

    def _drain_events(self, t: float) -> None:
        q = self._events
        while q is not None and not q.empty():
            e = q.get_nowait()
            if e.get("event") == CLOCK_EVENT:  # the lockstep clock's tick, not the world's
                continue
            if e.get("event") == "item_picked_up" and e.get("entity") is not None:
                self._picked[e["entity"]] = e.get("player")
            self._write({"type": "event", "t": t, "event": e})

    async def _frame(self, start: bool = False, stop: bool = False) -> None:
        f = await self.server.control.replay_frame(start, stop)
        t = self.now()
        self._drain_events(t)
        self.frames += 1
        self._write({"type": "frame", "t": t, "tick": f["tick"], "players": f["players"]})
        if f["blocks"]:
            self._write({"type": "blocks_changed", "t": t, "blocks": f["blocks"]})
        items = {i[0]: i for i in f["items"]}
        for eid, (_, item, count, x, y, z) in items.items():
            old = self._items.get(eid)
            if old is None or old[2] != count:
                self._write({"type": "item", "t": t, "id": eid, "item": item, "count": count, "pos": [x, y, z]})
        for eid in self._items.keys() - items.keys():
            self._write({"type": "item_gone", "t": t, "id": eid, "by": self._picked.pop(eid, None)})
        self._items = items
        mobs = {m[0]: m for m in f["mobs"]}
        for eid, (_, name, x, y, z, health) in mobs.items():
            old = self._mobs.get(eid)
            if old is None or old[2:] != [x, y, z, health]:
                self._write({"type": "mob", "t": t, "id": eid, "name": name, "pos": [x, y, z], "health": health})
        for eid in self._mobs.keys() - mobs.keys():
            self._write({"type": "mob_gone", "t": t, "id": eid})
        self._mobs = mobs

    def score(self, t: float, scores: dict[str, float]) -> None:
        """The teams' scores at game second `t` (the match's timeline)."""
        self._write({"type": "score", "t": t, "scores": scores})

    def program(self, player: str, what: str, message: str | None = None) -> None:
        """A player's program: `start` (the n-th run this episode), `error` (message), `end`."""
        if what == "start":
            self._runs[player] = self._runs.get(player, 0) + 1
        rec = {"type": "program", "t": self.now(), "player": player, "what": what, "run": self._runs.get(player, 0)}
        if message:
            rec["message"] = message[:500]
        self._write(rec)

    async def stop(self, final: dict[str, float] | None = None) -> None:
        self._stopping = True
        if self._task:
            self._task.cancel()
            await asyncio.wait({self._task}, timeout=STOP_WAIT_S)
        if self.error is None:
            try:
                await self._frame(stop=True)
            except Exception as exc:  # noqa: BLE001 - the server died: the recording ends here
                self.error = f"{type(exc).__name__}: {exc}"
        if self._events is not None:
            self.server.control.unsubscribe(self._events)
        end: dict[str, Any] = {"type": "end", "t": self.now(), "frames": self.frames}
        if final is not None:
            end["scores"] = final
        if self.error:
            end["error"] = self.error
        self._write(end)
        if self._file is not None:
            self._file.close()
            self._file = None
