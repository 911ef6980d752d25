"""The machine's load and the scores: when was an episode played under lag, and how many matches
may run at once (docs/performance.md).

Bots act in real time: a starved CPU makes players slower and scores lower. So every episode
records the server's ticks per second and each bot's physics-tick lag (measured in the bot
process, js/bot/lag.js), and `lag_verdict` flags it when any of them crosses a threshold below.
The default `parallel` comes from measured headroom: the cores free now (CPU count minus the
load average of others) over what one match costs (`MATCH_CORES`, from benchmarks/match_cost.py).
The lockstep clock's matches are bound by the CPU instead (they cannot lag, they go as fast as it
lets them): `choose_parallel_lockstep` runs as many as the cores run without slowing each other, and
`core_speed_ms` is this machine's speed per core now, a cheap probe the plan scales lockstep's
measured cost by (experiments/plan_clock.py).
"""

from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass

# An episode is flagged `lagged` when any of these is crossed during its game.
SERVER_TPS_MIN = 19.0  # server game ticks per wall second (20 nominal): over 5 % of its ticks lost
BOT_TICK_RATE_MIN = 19.0  # a bot's physics ticks per wall second (20 nominal): over 5 % lost
BOT_LATE_MEAN_MS_MAX = 10.0  # a bot's mean physics-tick lateness (an idle machine: under 1 ms)
BOT_LATE_PCT_MAX = 2.0  # % of a bot's physics ticks more than a whole tick (50 ms) late

# CPU cores one built-in match uses while playing (bots + server + Python), the worst of the two
# scenarios in benchmarks/match_cost.py (docs/performance.md has the table).
MATCH_CORES = 0.35
# Share of the free cores the matches may take; the rest absorbs bursts (logins, arena resets).
HEADROOM = 0.8
# CPU cores one lockstep match of built-in teams takes: it goes as fast as the CPU lets it, each tick
# waiting on its slowest process. Between the run's CPU time over its wall at parallel=1 (0.56 and 0.71,
# `python benchmarks/plan_accuracy.py --clock lockstep --parallel 1`, the machine loaded) and what fits
# docs/clock.md's 16 episodes at 2, 3 and 4 matches at once on 2 idle cores (each match 1.38 and 1.74
# times slower at 3 and 4 than at 2: 0.87 a match); docs/experiments.md.
LOCKSTEP_MATCH_CORES = 0.8


def lag_verdict(server_tps: float | None, bots: dict[str, dict | None]) -> tuple[bool, str | None]:
    """(lagged, reason) from the server's ticks per second and each bot's lag record (a dict from
    Player.lag: tick_rate, late_mean_ms, late_pct; None when it could not be read)."""
    reasons = []
    if server_tps is not None and server_tps < SERVER_TPS_MIN:
        reasons.append(f"server at {server_tps:g} TPS (< {SERVER_TPS_MIN:g})")
    for name, lag in sorted(bots.items()):
        if not lag:
            continue
        rate, late, pct = lag.get("tick_rate"), lag.get("late_mean_ms"), lag.get("late_pct")
        if rate is not None and rate < BOT_TICK_RATE_MIN:
            reasons.append(f"{name} at {rate:g} physics ticks/s (< {BOT_TICK_RATE_MIN:g})")
        if late is not None and late > BOT_LATE_MEAN_MS_MAX:
            reasons.append(f"{name} ticks {late:g} ms late on average (> {BOT_LATE_MEAN_MS_MAX:g})")
        if pct is not None and pct > BOT_LATE_PCT_MAX:
            reasons.append(f"{name}: {pct:g} % of ticks over 50 ms late (> {BOT_LATE_PCT_MAX:g} %)")
    return bool(reasons), "; ".join(reasons) or None


# How each clock's choice explains itself (ParallelChoice.explain).
_EXPLAIN = {
    "real": "parallel={parallel} chosen from headroom: {cpus} cores, load average {load:.2f} ({free:.2f} free), "
    "about {match_cores:g} core per match, {headroom:.0%} of the free cores (give parallel=N to choose)",
    "lockstep": "parallel={parallel} chosen for the lockstep clock's CPU-bound play: {cpus} cores, about "
    "{match_cores:g} core per match alone, as many as run without slowing each other (give parallel=N to choose)",
}


@dataclass(frozen=True)
class ParallelChoice:
    parallel: int
    cpus: int
    load: float  # 1-minute load average when chosen
    match_cores: float
    clock: str = "real"

    def explain(self) -> str:
        """One line saying how the value was chosen."""
        free = max(0.0, self.cpus - self.load)
        return _EXPLAIN[self.clock].format(
            parallel=self.parallel,
            cpus=self.cpus,
            load=self.load,
            free=free,
            match_cores=self.match_cores,
            headroom=HEADROOM,
        )


def choose_parallel(
    cpus: int | None = None, load: float | None = None, match_cores: float = MATCH_CORES
) -> ParallelChoice:
    """How many matches to run at once: as many as fit in HEADROOM of the cores others leave free
    (CPU count minus the 1-minute load average), at least one."""
    cpus = cpus if cpus is not None else (os.cpu_count() or 1)
    if load is None:
        try:
            load = os.getloadavg()[0]
        except OSError:  # not available on this platform
            load = 0.0
    free = max(0.0, cpus - load)
    parallel = max(1, math.floor(free * HEADROOM / match_cores + 1e-9))
    return ParallelChoice(parallel=parallel, cpus=cpus, load=round(load, 2), match_cores=match_cores)


def choose_parallel_lockstep(
    cpus: int | None = None, load: float | None = None, match_cores: float = LOCKSTEP_MATCH_CORES
) -> ParallelChoice:
    """How many lockstep matches to run at once: as many as the cores run without slowing each other
    (cpus / match_cores), at least one. A lockstep game cannot lag, so others' load is not held back
    for (it slows every match alike, however many there are); more matches than that share the cores
    and each goes slower (experiments/plan_clock.py)."""
    cpus = cpus if cpus is not None else (os.cpu_count() or 1)
    parallel = max(1, math.floor(cpus / match_cores + 1e-9))
    return ParallelChoice(parallel, cpus, round(load or 0.0, 2), match_cores, clock="lockstep")


# The default `parallel` of each clock (experiments/runner.local_parallel).
CHOOSE_PARALLEL = {"real": choose_parallel, "lockstep": choose_parallel_lockstep}


# The speed probe: a fixed piece of pure-Python work (about 1.06 ms on a core of the 2-core development
# machine), repeated for SPEED_PROBE_S of the wall clock; its fastest try is the core's own speed, which
# the load of the moment leaves out (1.057 to 1.06 ms at load average 10, where the mean of a longer
# work's tries read 2 to 3 times its fastest: how busy the machine is, the plan reads from the load
# average instead).
SPEED_PROBE_STEPS = 20_000
SPEED_PROBE_S = 0.2


def _probe_work() -> int:
    x = 0
    for i in range(SPEED_PROBE_STEPS):
        x = (x * 31 + i) % 1_000_003
    return x


def core_speed_ms(seconds: float = SPEED_PROBE_S) -> float:
    """This machine's speed per core now: milliseconds of the probe's fixed work, its fastest try in
    `seconds` of the wall clock (larger is slower)."""
    t0 = time.perf_counter()
    best = math.inf
    tries = 0
    while tries < 3 or time.perf_counter() - t0 < seconds:
        start = time.perf_counter()
        _probe_work()
        best = min(best, time.perf_counter() - start)
        tries += 1
    return round(best * 1000, 3)
