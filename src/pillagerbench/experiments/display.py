"""The live view of a match: the clock and both scores. A rich live panel in a terminal, plain
lines (every 10 s of game) in logs."""

from __future__ import annotations

import sys
from collections import deque

from rich.console import Console
from rich.live import Live
from rich.table import Table

from pillagerbench.config.schema import default
from pillagerbench.experiments.outage import Status

SHOWN = 5  # finished episodes the live panel shows


class MatchDisplay:
    def __init__(self, title: str, mode: str = default("display")):
        self.title = title
        self.console = Console(stderr=False)
        self.live_mode = mode == "live" or (mode == "auto" and sys.stdout.isatty())
        self.live: Live | None = None
        self.finished: deque[str] = deque(maxlen=SHOWN)  # the last episodes shown (a day of play keeps no more)
        self.waiting: Status | None = None  # the series waits for its provider or team server (experiments/outage.py)
        self.probes_shown = 0

    def __enter__(self) -> MatchDisplay:
        if self.live_mode:
            self.live = Live(self._table({}), console=self.console, refresh_per_second=4, transient=False)
            self.live.__enter__()
        return self

    def __exit__(self, *exc) -> None:
        if self.live:
            self.live.__exit__(*exc)

    def _table(self, s: dict) -> Table:
        table = Table(title=self.title)
        for col in ("episode", "clock", "red", "blue"):
            table.add_column(col, justify="right")
        for line in self.finished:
            table.add_row(*line.split("|"))
        if s:
            table.add_row(str(s["episode"]), f"{s['t']:>3.0f}/{s['length']:.0f} s", f"{s['red']:g}", f"{s['blue']:g}")
        if self.waiting:
            table.caption = self.waiting.line()
        return table

    def outage(self, status: Status | None) -> None:
        """The one live line while the series waits (None: it no longer does); in logs a line per probe."""
        self.waiting = status
        if self.live:
            self.live.update(self._table({}))
        elif status and status.probes != self.probes_shown:
            self.probes_shown = status.probes
            print(status.line(), flush=True)
        elif status is None:
            self.probes_shown = 0

    def tick(self, s: dict) -> None:
        if self.live:
            self.live.update(self._table(s))
        elif int(s["t"]) % 10 == 0 or s["t"] >= s["length"]:
            print(
                f"episode {s['episode']} t={s['t']:.0f}/{s['length']:.0f}s red={s['red']:g} blue={s['blue']:g}",
                flush=True,
            )

    def episode_done(self, rec) -> None:
        line = (
            f"{rec.episode}|{rec.status}|{rec.red_score if rec.red_score is not None else '-'}|"
            f"{rec.blue_score if rec.blue_score is not None else '-'}"
        )
        self.finished.append(line)
        message = (
            f"episode {rec.episode}: red {rec.red} {rec.red_score} - blue {rec.blue} {rec.blue_score} "
            f"({rec.winner or rec.status}{': ' + rec.error if rec.error else ''}) in {rec.duration_s:.1f} s"
        )
        for side, problems in (rec.problems or {}).items():
            message += f"\n  {side} {getattr(rec, side)}: " + "; ".join(problems)
        if self.live:
            self.live.console.print(message)
        else:
            print(message, flush=True)
