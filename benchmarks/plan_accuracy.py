"""How good is `plan=true`'s wall time? (issue 31, "A plan before a run"). Prints JSON.

Default: the plan of `pillagerbench run experiment=calibration experiment.episodes=1` (10 series of
one 120 s episode), then that command run for real (with the plan's `parallel`, so both schedule
the same way), and the error of the estimate (target: within 20 %), with the load average before
and after (other work on the machine slows series set-up).

--overheads: the measurement behind experiments/plan.py's SERIES_OVERHEAD_S, EPISODE_OVERHEAD_S and
RUN_OVERHEAD_S: one series per scenario of two 20 s do_nothing episodes at parallel=1; per episode
its recorded duration minus episode_length, per series its wall (series.json written at its start,
episodes.jsonl's last line at its end) minus its episodes' durations, per run the command's wall
minus its series' walls.

--clock lockstep: the same on the lockstep clock (issue 55, "The plan knows the clock"), by default
`experiment=fidelity experiment.episodes=1 episode_length=30` (8 series of built-in teams, each
against do_nothing); beside the error it prints what experiments/plan_clock.py's constants are made
of: each episode's wall seconds per game second (`game_s` / episode_length, and per scenario) and
overhead (its duration minus its game), that cost divided by the share of the cores the plan gave the
matches at the load average before the run and by the speed probe's ratio (`alone_wall_per_game_s`:
what LOCKSTEP_WALL_PER_GAME_S is made of), the speed probe (host/machine.core_speed_ms) before, during
(every 3 s) and after, and the cores the run's processes used (their CPU time over the run's wall).

    python benchmarks/plan_accuracy.py [--parallel N] [--episode-length 120]
    python benchmarks/plan_accuracy.py --overheads
    python benchmarks/plan_accuracy.py --clock lockstep [--parallel N] [--episode-length 30] [--episodes 1]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))
from pillagerbench.config.compose import load_config
from pillagerbench.experiments.plan import build_plan
from pillagerbench.experiments.plan_clock import Machine, lockstep_share
from pillagerbench.host.machine import core_speed_ms

COMMAND = [sys.executable, "-m", "pillagerbench.cli", "run"]


def run(args: list[str], cwd: Path) -> float:
    """Wall seconds of one `pillagerbench run` (its output to cwd/out.txt)."""
    t0 = time.monotonic()
    with open(cwd / "out.txt", "w") as out:
        code = subprocess.call([*COMMAND, *args], cwd=cwd, stdout=out, stderr=subprocess.STDOUT)
    wall = time.monotonic() - t0
    if code != 0:
        raise SystemExit(f"pillagerbench run exited {code}; see {cwd / 'out.txt'}")
    return wall


def series_figures(run_dir: Path, length: float) -> list[dict]:
    rows = []
    for d in sorted((run_dir / "series").iterdir()):
        durations = [json.loads(line)["duration_s"] for line in (d / "episodes.jsonl").read_text().splitlines()]
        wall = (d / "episodes.jsonl").stat().st_mtime - (d / "series.json").stat().st_mtime
        rows.append(
            {
                "series": d.name,
                "wall_s": round(wall, 2),
                "episode_overheads_s": [round(x - length, 3) for x in durations],
                "series_overhead_s": round(wall - sum(durations), 2),
            }
        )
    return rows


def overheads(tmp: Path) -> dict:
    length = 20.0
    args = [
        "experiment=calibration",
        "experiment.blue_teams=[do_nothing]",
        "experiment.episodes=2",
        f"episode_length={length:g}",
        "parallel=1",
        "display=plain",
        f"run_dir={tmp / 'run'}",
    ]
    load_before = os.getloadavg()
    wall = run(args, tmp)
    rows = series_figures(tmp / "run", length)
    episode = [x for r in rows for x in r["episode_overheads_s"]]
    return {
        "command": "pillagerbench run " + " ".join(args[:-1]),
        "load_average_before": load_before,
        "load_average_after": os.getloadavg(),
        "series": rows,
        "EPISODE_OVERHEAD_S": round(sum(episode) / len(episode), 2),
        "SERIES_OVERHEAD_S": round(sum(r["series_overhead_s"] for r in rows) / len(rows), 2),
        "RUN_OVERHEAD_S": round(wall - sum(r["wall_s"] for r in rows), 2),
    }


def children_cpu_s() -> float:
    """CPU seconds of every finished child process (and the children they waited for)."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


class SpeedSampler:
    """The speed probe every few seconds while a run plays (in a thread: the main one only waits)."""

    def __init__(self, every_s: float = 3.0) -> None:
        self.samples: list[float] = []
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._loop, args=(every_s,), daemon=True)

    def _loop(self, every_s: float) -> None:
        while not self._stop.wait(every_s):
            self.samples.append(core_speed_ms())

    def __enter__(self) -> SpeedSampler:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join()

    def mean(self) -> float | None:
        return round(statistics.fmean(self.samples), 3) if self.samples else None


def lockstep_figures(run_dir: Path, length: float) -> dict:
    """What a lockstep run's episodes cost on the wall: per game second (each, and per scenario) and
    beyond the game."""
    recs = [json.loads(line) for p in run_dir.glob("series/*/episodes.jsonl") for line in p.read_text().splitlines()]
    recs = [r for r in recs if r.get("game_s")]
    per_game_s = sorted(r["game_s"] / length for r in recs)
    overheads = [r["duration_s"] - r["game_s"] for r in recs]
    by_scenario = {
        sc: round(statistics.fmean(r["game_s"] / length for r in recs if r["scenario"] == sc), 3)
        for sc in sorted({r["scenario"] for r in recs})
    }
    return {
        "wall_per_game_s": [round(x, 3) for x in per_game_s],
        "wall_per_game_s_mean": round(statistics.fmean(per_game_s), 3) if per_game_s else None,
        "wall_per_game_s_by_scenario": by_scenario,
        "episode_overhead_s_mean": round(statistics.fmean(overheads), 2) if overheads else None,
        "stalled_or_failed": sum(1 for r in recs if r.get("stalled") or r.get("status") == "failed"),
    }


def accuracy(tmp: Path, parallel: int | None, length: float, clock: str, experiment: str, episodes: int) -> dict:
    args = [f"experiment={experiment}", f"experiment.episodes={episodes}", f"episode_length={length:g}"]
    args += [f"clock={clock}"] if clock != "real" else []
    args += [f"parallel={parallel}"] if parallel else []
    load_before, speed_before = os.getloadavg(), core_speed_ms()
    plan = build_plan(load_config(args), args)
    estimate = plan.wall_low  # no LLM team: low = high
    runs = [*args, *([] if parallel else [f"parallel={plan.parallel}"]), "display=plain", f"run_dir={tmp / 'run'}"]
    cpu_before = children_cpu_s()
    with SpeedSampler() as sampler:
        measured = run(runs, tmp)
    target = 0.25 if clock == "lockstep" else 0.2
    out = {
        "command": "pillagerbench run " + " ".join(runs[:-1]),
        "series": len(plan.series),
        "episodes": plan.episodes,
        "parallel": plan.parallel,
        "clock": plan.clock,
        "load_average_before": load_before,
        "load_average_after": os.getloadavg(),
        "core_speed_ms": {"before": speed_before, "during_mean": sampler.mean(), "after": core_speed_ms()},
        "cores_used": round((children_cpu_s() - cpu_before) / measured, 2),
        "plan_wall_s": round(estimate, 1),
        "measured_wall_s": round(measured, 1),
        "error_pct": round(100 * (estimate - measured) / measured, 1),
        f"within_{round(target * 100)}_pct": abs(estimate - measured) <= target * measured,
        "per_series": series_figures(tmp / "run", length),
    }
    if clock == "lockstep":
        figures = out["lockstep"] = lockstep_figures(tmp / "run", length)
        machine = Machine(os.cpu_count() or 1, load_before[0], speed_before)
        at_once = min(plan.parallel, len(plan.series))
        if figures["wall_per_game_s_mean"]:  # what plan_clock's LOCKSTEP_WALL_PER_GAME_S is made of
            alone = figures["wall_per_game_s_mean"] / (lockstep_share(at_once, machine) * machine.speed)
            figures["alone_wall_per_game_s"] = round(alone, 4)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--overheads", action="store_true", help="measure the plan's overhead constants instead")
    ap.add_argument("--parallel", type=int, default=None, help="default: the plan's choice from the load")
    ap.add_argument("--clock", choices=["real", "lockstep"], default="real")
    ap.add_argument("--experiment", default=None, help="default: calibration (real clock), fidelity (lockstep)")
    ap.add_argument("--episodes", type=int, default=1, help="experiment.episodes")
    ap.add_argument("--episode-length", type=float, default=None, help="default: 120 (real clock), 30 (lockstep)")
    a = ap.parse_args()
    lockstep = a.clock == "lockstep"
    experiment = a.experiment or ("fidelity" if lockstep else "calibration")
    length = a.episode_length or (30.0 if lockstep else 120.0)
    with tempfile.TemporaryDirectory(prefix="plan_accuracy_") as d:
        if a.overheads:
            result = overheads(Path(d))
        else:
            result = accuracy(Path(d), a.parallel, length, a.clock, experiment, a.episodes)
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
