"""Progress of an experiment: episodes done out of all, ETA, and the scores of the episodes being
played. In a terminal a live bar and table (rich); in logs plain lines (one per finished
episode, and a summary every `plain_every` seconds).

It reads only the run directory (episodes.jsonl and live.json of each series), so it shows the
same thing whether the series run in this process or on Ray workers.
"""

from __future__ import annotations

import asyncio
import sys
import time
from pathlib import Path
from typing import Any

from rich.console import Console, Group
from rich.live import Live
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn
from rich.table import Table

from pillagerbench.config.schema import default
from pillagerbench.experiments.outage import Status, read_status
from pillagerbench.rundir import EpisodeRecord, RunDir, progress, spoiled


def fmt_duration(seconds: float | None) -> str:
    if seconds is None:
        return "?"
    seconds = int(max(0, seconds))
    h, rest = divmod(seconds, 3600)
    m, s = divmod(rest, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m}:{s:02d}"


def waiting_line(waiting: list[tuple[Any, Status]]) -> str:
    """The one live line of the series waiting for a provider or team server (experiments/outage.py)."""
    spec, first = min(waiting, key=lambda w: w[1].since)
    more = f" (and {len(waiting) - 1} more series)" if len(waiting) > 1 else ""
    return f"{spec.id}{more}: {first.line()}"


class ExperimentProgress:
    def __init__(
        self,
        run_dir: Path,
        specs: list,
        title: str,
        *,
        parallel: int = 1,
        mode: str = default("display"),
        episode_length: float = 120.0,
        interval: float = 1.0,
        plain_every: float = 60.0,
        stream=None,
        dirs: dict[str, Path] | None = None,
    ):
        self.dirs = dirs or {}
        self.run_dir, self.specs, self.title = Path(run_dir), specs, title
        self.parallel, self.episode_length = max(1, parallel), float(episode_length)
        self.interval, self.plain_every = interval, plain_every
        self.stream = stream or sys.stdout
        self.live_mode = mode == "live" or (mode == "auto" and self.stream.isatty())
        self.total = sum(s.episodes for s in specs)
        self._cache: dict[str, tuple[tuple, dict]] = {}
        self.start_time = time.monotonic()
        self.start_done: int | None = None
        self._reported: dict[str, int] = {}
        self._probes: dict[str, int] = {}  # the probes shown of each series waiting (experiments/outage.py)
        self._last_plain = 0.0
        self._task: asyncio.Task | None = None
        self._live: Live | None = None
        self._progress: Progress | None = None

    # -- reading the run directory --------------------------------------------------------------
    def series_dir(self, spec) -> Path:
        return self.dirs.get(spec.id) or RunDir(self.run_dir).series_dir(spec.id)

    def finished(self, spec) -> dict[int, EpisodeRecord]:
        path = RunDir(self.series_dir(spec)).episodes_path
        try:
            st = path.stat()
            key = (st.st_size, st.st_mtime_ns)
        except FileNotFoundError:
            return {}
        cached = self._cache.get(spec.id)
        if cached and cached[0] == key:
            return cached[1]
        done = RunDir(self.series_dir(spec)).finished()
        self._cache[spec.id] = (key, done)
        return done

    def snapshot(self) -> dict:
        done = failed = 0
        running, waiting = [], []
        for spec in self.specs:
            fin = self.finished(spec)
            settled = progress(fin, spec.episodes, spec.config.retries)  # a spoiled episode is played again
            done += settled.used + settled.given_up
            failed += sum(not r.ok for r in fin.values())
            status = RunDir(self.series_dir(spec)).read_live() if not settled.complete else None
            if status is not None:
                running.append((spec, status))
            outage = read_status(self.series_dir(spec)) if not settled.complete else None
            if outage is not None:
                waiting.append((spec, outage))
        if self.start_done is None:
            self.start_done = done
        elapsed = time.monotonic() - self.start_time
        new = done - self.start_done
        remaining = self.total - done
        if new > 0:
            eta = remaining * elapsed / new
        else:  # no episode finished yet in this session: a guess from the episode length
            eta = remaining * (self.episode_length + 6.0) / min(self.parallel, max(1, len(self.specs)))
        return {
            "done": done,
            "total": self.total,
            "failed": failed,
            "running": running,
            "waiting": waiting,
            "eta_s": eta,
            "elapsed_s": elapsed,
        }

    # -- rendering -------------------------------------------------------------------------------
    def _table(self, snap: dict) -> Table:
        table = Table(show_edge=False, box=None)
        for col in ("series", "episode", "clock", "red", "blue"):
            table.add_column(col, justify="left" if col == "series" else "right")
        for spec, live in snap["running"]:
            table.add_row(
                f"{spec.red} vs {spec.blue} ({spec.scenario})",
                f"{live.episode + 1}/{spec.episodes}",
                f"{live.t:.0f}/{live.length:.0f} s",
                f"{live.red:g}",
                f"{live.blue:g}",
            )
        if snap.get("waiting"):
            table.caption = waiting_line(snap["waiting"])
        return table

    def _plain(self, snap: dict, force: bool = False) -> None:
        for spec in self.specs:
            fin = self.finished(spec)
            seen = self._reported.get(spec.id, 0)
            for i in sorted(fin)[seen:]:
                r = fin[i]
                print(
                    f"[{snap['done']}/{snap['total']}] {spec.id} episode {i}: red {spec.red} {r.red_score} - "
                    f"blue {spec.blue} {r.blue_score} ({r.winner or r.status})"
                    + (f"; spoiled on our side ({kind}): in no score" if (kind := spoiled(r)) else ""),
                    file=self.stream,
                    flush=True,
                )
            self._reported[spec.id] = len(fin)
        for spec, outage in snap.get("waiting", []):
            if self._probes.get(spec.id) != outage.probes:  # a line per probe
                self._probes[spec.id] = outage.probes
                print(f"{spec.id}: {outage.line()}", file=self.stream, flush=True)
        now = time.monotonic()
        if force or now - self._last_plain >= self.plain_every:
            self._last_plain = now
            playing = "; ".join(
                f"{s.red} vs {s.blue} ep {lv.episode} t={lv.t:.0f}s {lv.red:g}-{lv.blue:g}" for s, lv in snap["running"]
            )
            print(
                f"{self.title}: {snap['done']}/{snap['total']} episodes ({snap['failed']} failed), "
                f"elapsed {fmt_duration(snap['elapsed_s'])}, ETA {fmt_duration(snap['eta_s'])}"
                + (f"; playing: {playing}" if playing else ""),
                file=self.stream,
                flush=True,
            )

    def update(self, force: bool = False) -> dict:
        snap = self.snapshot()
        if self._progress is not None and self._live is not None:
            self._progress.update(
                self._bar, completed=snap["done"], eta=fmt_duration(snap["eta_s"]), failed=snap["failed"]
            )
            self._live.update(Group(self._progress, self._table(snap)))
        else:
            self._plain(snap, force)
        return snap

    async def _loop(self) -> None:
        while True:
            self.update()
            await asyncio.sleep(self.interval)

    def __enter__(self) -> ExperimentProgress:
        snap = self.snapshot()
        for spec in self.specs:
            self._reported[spec.id] = len(self.finished(spec))
        if self.live_mode:
            self._progress = Progress(
                TextColumn("[bold]{task.description}"),
                BarColumn(),
                MofNCompleteColumn(),
                TextColumn("episodes, {task.fields[failed]} failed"),
                TimeElapsedColumn(),
                TextColumn("ETA {task.fields[eta]}"),
                console=Console(file=self.stream),
            )
            self._bar = self._progress.add_task(
                self.title,
                total=self.total,
                completed=snap["done"],
                eta=fmt_duration(snap["eta_s"]),
                failed=snap["failed"],
            )
            self._live = Live(
                Group(self._progress, self._table(snap)), console=Console(file=self.stream), refresh_per_second=2
            )
            self._live.__enter__()
        else:
            self._last_plain = time.monotonic()
            print(
                f"{self.title}: {snap['done']}/{snap['total']} episodes already done; {len(self.specs)} series",
                file=self.stream,
                flush=True,
            )
        self._task = asyncio.get_running_loop().create_task(self._loop())
        return self

    def __exit__(self, *exc) -> None:
        if self._task:
            self._task.cancel()
        self.update(force=True)
        if self._live:
            self._live.__exit__(*exc)
