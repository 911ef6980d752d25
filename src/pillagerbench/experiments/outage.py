"""Waiting out an outage (`outage_wait_s`; docs/experiments.md, "Waiting out an outage").

After an episode in which a side could not reach what it plays with (its LLM provider answered none of
its calls, the last for want of an answer: `llm.preflight.UNANSWERED`, connection refused, name not
resolved, time-outs, 5xx, 429; or a remote team's server could not be reached: the team's
`unreachable`), the series ends its match (server and bots closed) and probes that with one short
request (`llm.preflight.probe`, the preflight's request; a team its `preflight`). Until it answers, the
series waits, probing again after FIRST_WAIT_S, doubling to MAX_WAIT_S, for up to `outage_wait_s`
since the first probe failed; then it plays on, on a fresh server, or, past the wait, stops (the run
says so in one line; `resume=RUN_DIR` waits again, then plays the rest). `outage_wait_s=0` never waits.

The episode is recorded as it happened, its record held back until the first probe has answered or
not: an LLM side whose provider answers no probe gets the problem `provider outage: ...` (a fault of
ours that spends no try: rundir/faults.py, rundir/schedule.py `NO_TRY`), so the episode played in its
place uses none of `retries`; a provider that answers the first probe was not out, and its spoiled
episode is an ordinary try. A remote team's server that did not answer stays the team's own fault
(scored, never played again: a team must not choose its episodes); the series only waits for it
before its next episode. `llm.preflight=false` sends no probe either (that side is not waited for).
Nothing a team spends (calls, budgets) is touched by the waiting. While a series waits, `outage.json`
in its directory says what does not answer, since when and when the next probe is (`Status`: the
progress display's live line).
"""

from __future__ import annotations

import asyncio
import json
import re
import time
from collections.abc import Callable, Mapping
from dataclasses import asdict, dataclass
from pathlib import Path

from pillagerbench.config.schema import RunConfig
from pillagerbench.config.sides import SIDES
from pillagerbench.llm.preflight import UNANSWERED
from pillagerbench.llm.preflight import probe as llm_probe
from pillagerbench.rundir import HARNESS, EpisodeRecord, RunDir, faults
from pillagerbench.rundir.whole import replace_json
from pillagerbench.teams import find_team

FIRST_WAIT_S = 5.0  # the wait before the second probe; doubled after each probe that finds it out
MAX_WAIT_S = 60.0
REFRESH_S = 1.0  # the live line's refresh while waiting
OUTAGE = "provider outage"  # an LLM side's problem when its provider answered no probe (rundir/faults.py)
PROVIDER = "provider unreachable"  # rundir/faults.py's kind of "llm failed on all ..." and of a failed call
FILE = "outage.json"  # in the series directory, while it waits
LLM, TEAM = "llm", "team"  # what a side's probe asks: its LLM provider, or its team (a remote team's server)
_ERROR = re.compile(r"(?:^|last: )(\w+):")  # the error type in a failed episode's error or a side's problem


def _probes_llm(cfg: RunConfig, side: str) -> bool:
    return bool(getattr(find_team(cfg.side(side).name), "uses_llm", False) and cfg.llm_of(side).preflight is not False)


def unreachable(rec: EpisodeRecord, cfg: RunConfig) -> dict[str, str]:
    """The sides of an episode that could not reach what they play with -> LLM or TEAM (what to probe)."""
    names = {cls.__name__ for cls in UNANSWERED}
    out: dict[str, str] = {}
    for f in faults(rec):
        error = _ERROR.search(f.what)
        if f.whose == HARNESS and f.kind == PROVIDER and error and error.group(1) in names:
            out.update({side: LLM for side in ([f.side] if f.side else SIDES) if _probes_llm(cfg, side)})
    for side in SIDES:
        check = getattr(find_team(cfg.side(side).name), "unreachable", None)
        if side not in out and callable(check) and check(rec.problems.get(side, [])):
            out[side] = TEAM
    return out


async def probe(cfg: RunConfig, sides: Mapping[str, str]) -> dict[str, str]:
    """One short request to what each of `sides` plays with; those that do not answer -> the line saying so."""

    async def one(side: str, what: str) -> str | None:
        if what == LLM:
            return await llm_probe(cfg.llm_of(side))
        team = cfg.side(side)
        return await find_team(team.name).preflight(dict(team.options))

    found = await asyncio.gather(*(one(side, what) for side, what in sides.items()))
    return {side: line for side, line in zip(sides, found) if line}


def mark(rec: EpisodeRecord, down: Mapping[str, str]) -> None:
    """Each LLM side whose provider answered no probe after the episode: its `provider outage` problem."""
    for side, line in down.items():
        rec.problems.setdefault(side, []).append(f"{OUTAGE}: no answer to a probe after the episode either: {line}")


def clock(t: float) -> str:
    return time.strftime("%H:%M:%S", time.localtime(t))


def span(seconds: float) -> str:
    seconds = int(max(0.0, seconds) + 0.5)
    m, s = divmod(seconds, 60)
    return f"{m} min {s} s" if m else f"{s} s"


@dataclass(frozen=True)
class Status:
    """A series waiting: what does not answer, since when, its next probe and the end of the wait (epoch s)."""

    what: str
    since: float
    next_probe: float
    until: float
    probes: int = 1

    def line(self, now: float | None = None) -> str:
        now = time.time() if now is None else now
        return (
            f"unreachable since {clock(self.since)} ({span(now - self.since)}), next probe in "
            f"{span(self.next_probe - now)}, waiting until {clock(self.until)}: {self.what}"
        )


def write_status(series_dir: Path, status: Status | None) -> None:
    """outage.json of a series: its Status while it waits, none otherwise."""
    path = Path(series_dir) / FILE
    if status is None:
        path.unlink(missing_ok=True)
        return
    replace_json(path, asdict(status))


def read_status(series_dir: Path) -> Status | None:
    try:
        return Status(**json.loads((Path(series_dir) / FILE).read_text()))
    except (OSError, ValueError, TypeError):
        return None


@dataclass(frozen=True)
class Stopped:
    """A series stopped past its wait: what did not answer, since when (epoch s), for how long."""

    what: str
    since: float
    waited_s: float

    def line(self, run_dir: Path | str, planned_left: int) -> str:
        """The run's one line about it."""
        return (
            f"gave up waiting after {span(self.waited_s)} (outage_wait_s): {self.what} did not answer since "
            f"{clock(self.since)}; {planned_left} planned episode(s) not played: resume={run_dir} plays them"
        )


class Waiter:
    """One series' waiting for what its sides play with (`outage_wait_s`; 0: it never waits)."""

    def __init__(
        self,
        cfg: RunConfig,
        rundir: RunDir,
        *,
        label: str = "",
        say: Callable[[str], None] = print,
        show: Callable[[Status | None], None] | None = None,
    ):
        self.cfg, self.rundir, self.label, self.say, self.show = cfg, rundir, label, say, show
        self.limit = float(cfg.outage_wait_s)

    def holds(self, rec: EpisodeRecord) -> bool:
        """Whether the series waits (its record held back until a probe) after this episode."""
        return self.limit > 0 and bool(unreachable(rec, self.cfg))

    async def after(self, rec: EpisodeRecord, commit: Callable[[EpisodeRecord], None]) -> Stopped | None:
        """After an episode that `holds`: probe, mark the LLM sides whose provider is out, commit the record
        (`commit`), and wait while something does not answer; a Stopped when the wait ran out."""
        sides = unreachable(rec, self.cfg)
        down = await probe(self.cfg, sides)
        mark(rec, {side: line for side, line in down.items() if sides[side] == LLM})
        commit(rec)
        return await self.wait(sides, down) if down else None

    async def again(self, finished: Mapping[int, EpisodeRecord]) -> Stopped | None:
        """Before a resumed series plays on: if its last episode could not reach something, wait for it again."""
        sides = unreachable(finished[max(finished)], self.cfg) if finished and self.limit > 0 else {}
        down = await probe(self.cfg, sides) if sides else {}
        return await self.wait(sides, down) if down else None

    async def wait(self, sides: Mapping[str, str], down: Mapping[str, str]) -> Stopped | None:
        """Probe with growing waits until everything answers (None) or `outage_wait_s` has passed (Stopped)."""
        since, start, pause, probes = time.time(), time.monotonic(), FIRST_WAIT_S, 1
        what = "; ".join(dict.fromkeys(down.values()))
        self.say(f"{self.label}{what}: no answer; waiting for it, up to outage_wait_s={self.limit:g} s")
        try:
            while (left := self.limit - (time.monotonic() - start)) > 0:
                await self._pause(Status(what, since, time.time() + min(pause, left), since + self.limit, probes))
                down, probes, pause = await probe(self.cfg, sides), probes + 1, min(pause * 2, MAX_WAIT_S)
                if not down:
                    self.say(f"{self.label}answered again after {span(time.time() - since)}: playing on")
                    return None
                what = "; ".join(dict.fromkeys(down.values()))
            return Stopped(what, since, time.monotonic() - start)
        finally:
            write_status(self.rundir.path, None)
            if self.show:
                self.show(None)

    async def _pause(self, status: Status) -> None:
        write_status(self.rundir.path, status)
        while (left := status.next_probe - time.time()) > 0:
            if self.show:
                self.show(status)
            await asyncio.sleep(min(REFRESH_S, left))
