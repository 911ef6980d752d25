"""The plan's wall time by clock: what one match's game second costs on the wall, and what a run's
overheads are, on the clock the run plays (docs/experiments.md, "Before a run: plan=true").

- real: a game second is a wall second (`episode_length` of wall time per episode); the overheads
  measured with `python benchmarks/plan_accuracy.py --overheads`.
- lockstep: the game runs as fast as the CPU lets it. A game second costs the scenario's
  LOCKSTEP_WALL_PER_GAME_S (built-in teams, one match on an idle core of the machine the probe read
  LOCKSTEP_SPEED_MS on), times this machine's speed now against then (host/machine.core_speed_ms: a
  core's own speed), times the share of the cores the match gets: `parallel` matches taking
  LOCKSTEP_MATCH_CORES each (host/machine.py) and the others' load (the 1-minute load average) share
  `cpus` cores, max(1, (parallel x LOCKSTEP_MATCH_CORES + load) / cpus) times slower than alone. The
  load of others is the least certain factor: it moves within minutes, and runs at like load averages
  went up to 1.8 times apart (docs/experiments.md). With `clock.speed` a
  number a game second costs at least 1/speed wall seconds. The overheads (a series' server start
  and logins, an episode's reset and the game's start, which waits for every bot's chunks, the run's
  start) are lockstep's own and CPU-bound too: they scale alike. All measured with `python
  benchmarks/plan_accuracy.py --clock lockstep` (docs/experiments.md has the runs).

LLM calls on the lockstep clock: the world waits for every call in flight, so a call costs wall time
and no game time. The pre-game's chain counts as on the real clock (the larger side's: both sides
think at once); in the game, each side's chain (its players ask at once, so one critic and one action
call per iteration) adds to the wall time, both sides' summed: while one side's call holds the world
the other side's runs cannot end, so the two seldom overlap. The low end has no call in the game (as
the call counts). On the real clock the game's calls happen within its `episode_length`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from pillagerbench.config.schema import ClockConfig
from pillagerbench.host.machine import LOCKSTEP_MATCH_CORES

# Measured by `python benchmarks/plan_accuracy.py --overheads` (do_nothing vs do_nothing, one series of
# two 20 s episodes per scenario, parallel=1), twice, on the 2-core development machine at load average 4-5
# (docs/experiments.md, "Before a run"): the mean of the four series and two runs.
SERIES_OVERHEAD_S = 8.0  # a series' arena server start, world load, bot logins (5.2-7.9 s MW, 6.1-12.6 s DD)
EPISODE_OVERHEAD_S = 0.45  # per episode beyond episode_length: arena and player reset, pre/post-game (0.15-0.93 s)
RUN_OVERHEAD_S = 2.6  # once per run: the command's start, config composition, checks (2.0 and 3.1 s)

# Lockstep: measured by `python benchmarks/plan_accuracy.py --clock lockstep [--parallel 1|2]
# --episode-length 60|30` (experiment=fidelity experiment.episodes=1: each built-in opponent against
# do_nothing; six runs) and four plain runs of two 15 or 30 s episodes, on the 2-core development
# machine with other engineers' tests running (load average 4 to 22; docs/experiments.md has the runs):
# each figure divided by its run's share of the cores (`lockstep_share`, at the load average before it)
# and its speed ratio, fitted over the runs. On an idle core of a machine whose probe reads
# LOCKSTEP_SPEED_MS, one match alone:
LOCKSTEP_WALL_PER_GAME_S = {"mushroom_war": 0.057, "dash_and_dine": 0.074}  # Dash & Dine has more bots (1.3x)
LOCKSTEP_DEFAULT_WALL_PER_GAME_S = 0.065  # a scenario not measured: the mean
LOCKSTEP_SERIES_OVERHEAD_S = 2.2  # server start, world load, logins (6.6 to 21.7 s as measured)
LOCKSTEP_EPISODE_OVERHEAD_S = 0.39  # reset and the game's start, beyond the game (0.4 to 2.3 s as measured)
LOCKSTEP_RUN_OVERHEAD_PER_SERIES_S = 0.2  # once per run and series: each series' config checked, its directory
LOCKSTEP_SPEED_MS = 1.06  # the speed probe then (host/machine.core_speed_ms: 0.94 to 1.06 ms)


@dataclass(frozen=True)
class Machine:
    """What the plan assumes of this machine: its cores, the load of others, its speed probe now."""

    cpus: int
    load: float
    speed_ms: float | None  # host/machine.core_speed_ms; None until a lockstep plan needs it

    @property
    def speed(self) -> float:
        """How much slower a core is now than when lockstep's cost was measured."""
        return (self.speed_ms or LOCKSTEP_SPEED_MS) / LOCKSTEP_SPEED_MS


@dataclass(frozen=True)
class ClockCost:
    """One clock's wall time: per game second of one match of a scenario and the overheads, each
    times `scale` (how much slower this machine makes them with `parallel` matches at once), and
    whether the game's LLM calls add wall time."""

    game_s: Callable[[str], float]
    series_overhead_s: float
    episode_overhead_s: float
    run_overhead_s: float
    run_overhead_per_series_s: float
    scale: Callable[[int, Machine], float]  # how much slower this machine makes all of it now

    game_calls_wait: bool  # the world waits for the game's LLM calls (they add wall time)
    says: Callable[[ClockConfig, int, Machine], str]

    def per_game_s(self, scenario: str, clock: ClockConfig, parallel: int, machine: Machine) -> float:
        """Wall seconds one game second of `scenario` costs, no faster than `clock.speed` paces it."""
        paced = 0.0 if clock.speed == "max" else 1.0 / float(clock.speed)  # the real clock's speed is 1
        return max(self.game_s(scenario) * self.scale(parallel, machine), paced)

    def overheads(self, parallel: int, machine: Machine, series: int) -> tuple[float, float, float]:
        """(per series, per episode, per run of `series` series) in wall seconds."""
        k = self.scale(parallel, machine)
        run = self.run_overhead_s + self.run_overhead_per_series_s * series
        return self.series_overhead_s * k, self.episode_overhead_s * k, run * k


def lockstep_share(parallel: int, machine: Machine) -> float:
    """How much slower each of `parallel` lockstep matches runs than one alone on idle cores: they
    and the others' load share the cores."""
    return max(1.0, (parallel * LOCKSTEP_MATCH_CORES + machine.load) / max(1, machine.cpus))


def _lockstep_scale(parallel: int, machine: Machine) -> float:
    return machine.speed * lockstep_share(parallel, machine)


def _says_real(clock: ClockConfig, parallel: int, machine: Machine) -> str:
    return "clock: real (a game second is a wall second)"


def _says_lockstep(clock: ClockConfig, parallel: int, machine: Machine) -> str:
    alone = ", ".join(f"{k} {v:g}" for k, v in LOCKSTEP_WALL_PER_GAME_S.items())
    return (
        f"clock: lockstep (wall seconds per game second: {alone} measured alone on an idle core, x{machine.speed:.2f} "
        f"for this machine's speed now, x{lockstep_share(parallel, machine):.2f} for {parallel} match(es) at once "
        f"on {machine.cpus} cores at load average {machine.load:.2f}; the overheads alike"
        + ("" if clock.speed == "max" else f"; no faster than clock.speed={clock.speed}")
        + ")"
    )


COSTS: dict[str, ClockCost] = {
    "real": ClockCost(
        lambda scenario: 1.0,
        SERIES_OVERHEAD_S,
        EPISODE_OVERHEAD_S,
        RUN_OVERHEAD_S,
        0.0,
        scale=lambda parallel, machine: 1.0,
        game_calls_wait=False,
        says=_says_real,
    ),
    "lockstep": ClockCost(
        lambda scenario: LOCKSTEP_WALL_PER_GAME_S.get(scenario, LOCKSTEP_DEFAULT_WALL_PER_GAME_S),
        LOCKSTEP_SERIES_OVERHEAD_S,
        LOCKSTEP_EPISODE_OVERHEAD_S,
        0.0,
        LOCKSTEP_RUN_OVERHEAD_PER_SERIES_S,
        scale=_lockstep_scale,
        game_calls_wait=True,
        says=_says_lockstep,
    ),
}
