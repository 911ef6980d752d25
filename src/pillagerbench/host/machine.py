"""The machine's load and the scores: when was an episode played under lag, and how many matches
may run at once (docs/performance.md).

Bots act in real time: a starved CPU makes players slower and scores lower. So every episode
records the server's ticks per second and each bot's physics-tick lag (measured in the bot
process, js/bot/lag.js), and `lag_verdict` flags it when any of them crosses a threshold below.
The default `parallel` comes from measured headroom: the cores free now (CPU count minus the
load average of others) over what one match costs (`MATCH_CORES`, from benchmarks/match_cost.py).
"""

from __future__ import annotations

import math
import os
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


@dataclass(frozen=True)
class ParallelChoice:
    parallel: int
    cpus: int
    load: float  # 1-minute load average when chosen
    match_cores: float

    def explain(self) -> str:
        """One line saying how the value was chosen."""
        free = max(0.0, self.cpus - self.load)
        return (
            f"parallel={self.parallel} chosen from headroom: {self.cpus} cores, load average {self.load:.2f} "
            f"({free:.2f} free), about {self.match_cores:g} core per match, {HEADROOM:.0%} of the free cores "
            "(give parallel=N to choose)"
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
