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

    python benchmarks/plan_accuracy.py [--parallel N] [--episode-length 120]
    python benchmarks/plan_accuracy.py --overheads
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))
from pillagerbench.config.compose import load_config
from pillagerbench.experiments.plan import build_plan

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


def accuracy(tmp: Path, parallel: int | None, length: float) -> dict:
    args = ["experiment=calibration", "experiment.episodes=1", f"episode_length={length:g}"]
    args += [f"parallel={parallel}"] if parallel else []
    load_before = os.getloadavg()
    plan = build_plan(load_config(args), args)
    estimate = plan.wall_low  # no LLM team: low = high
    runs = [*args, *([] if parallel else [f"parallel={plan.parallel}"]), "display=plain", f"run_dir={tmp / 'run'}"]
    measured = run(runs, tmp)
    return {
        "command": "pillagerbench run " + " ".join(runs[:-1]),
        "series": len(plan.series),
        "episodes": plan.episodes,
        "parallel": plan.parallel,
        "load_average_before": load_before,
        "load_average_after": os.getloadavg(),
        "plan_wall_s": round(estimate, 1),
        "measured_wall_s": round(measured, 1),
        "error_pct": round(100 * (estimate - measured) / measured, 1),
        "within_20_pct": abs(estimate - measured) <= 0.2 * measured,
        "per_series": series_figures(tmp / "run", length),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--overheads", action="store_true", help="measure the plan's overhead constants instead")
    ap.add_argument("--parallel", type=int, default=None, help="default: the plan's choice from the load")
    ap.add_argument("--episode-length", type=float, default=120.0)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="plan_accuracy_") as d:
        result = overheads(Path(d)) if a.overheads else accuracy(Path(d), a.parallel, a.episode_length)
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
