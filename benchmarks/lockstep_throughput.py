"""Lockstep against the real clock (issue "Game time, not wall time"): episodes per hour of built-in
teams on this machine, the fidelity experiment (every built-in opponent of both scenarios against
do_nothing) played on each clock, and the wall time of the whole run. Prints JSON.

    python benchmarks/lockstep_throughput.py [--episodes 1] [--length 120] [--real-parallel 4]
        [--lockstep-parallel 4] [--only lockstep|real] [--keep DIR]

`--episodes 10` is the suite's reference run (80 episodes). Each run is `pillagerbench run
experiment=fidelity scoring=upstream protocol=upstream` (as scripts/reference_figures.py's), in a
subprocess; the episodes counted are those recorded, failed or flagged ones reported apart.
`machine_us_per_node` is this machine's speed per core before and after the run (`machine_speed`):
lockstep's figure moves with it, the real clock's does not.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CLI = [sys.executable, "-m", "pillagerbench.cli"]
sys.path.insert(0, str(Path(__file__).resolve().parent))
from path_search import measure  # noqa: E402  (a sibling script)


def play(clock: str, parallel: int, episodes: int, length: float, run_dir: Path) -> dict:
    cmd = [
        *CLI, "run", "experiment=fidelity", f"experiment.episodes={episodes}", f"episode_length={length}",
        "scoring=upstream", "protocol=upstream", f"clock={clock}", f"parallel={parallel}",
        f"run_dir={run_dir}", "display=plain",
    ]  # fmt: skip
    started = time.monotonic()
    proc = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    wall = time.monotonic() - started
    if proc.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{proc.stdout[-2000:]}\n{proc.stderr[-2000:]}")
    recs = [json.loads(line) for p in run_dir.glob("series/*/episodes.jsonl") for line in p.read_text().splitlines()]
    ok = [r for r in recs if r.get("status") != "failed" and not r.get("lagged")]
    return {
        "clock": clock,
        "parallel": parallel,
        "episodes": len(recs),
        "failed_or_lagged": len(recs) - len(ok),
        "wall_s": round(wall, 1),
        "episodes_per_hour": round(len(ok) / wall * 3600, 1),
        "run_dir": str(run_dir),
    }


def machine_speed() -> float:
    """This machine's speed per core this hour: the path search's fixed work (benchmarks/path_search.py),
    microseconds per node. The real clock's episodes per hour do not depend on it (they are bound by
    wall time); lockstep's do, so a speedup is this machine's, at this hour, and two runs compare only
    at like figures (this 2-core machine has read from 18 to 39 within a day)."""
    return measure(3)["ours"]["us_per_node"]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--episodes", type=int, default=1, help="per opponent (10 = the reference run)")
    ap.add_argument("--length", type=float, default=120.0)
    ap.add_argument("--real-parallel", type=int, default=4)
    ap.add_argument("--lockstep-parallel", type=int, default=4)
    ap.add_argument("--only", choices=["real", "lockstep"])
    ap.add_argument("--keep", type=Path, help="write the run directories here (default: a temporary directory)")
    args = ap.parse_args()
    base = args.keep or Path(tempfile.mkdtemp(prefix="lockstep-bench-"))
    out: dict = {"machine_us_per_node": {"before": machine_speed()}}
    for clock, parallel in (("lockstep", args.lockstep_parallel), ("real", args.real_parallel)):
        if args.only in (None, clock):
            out[clock] = play(clock, parallel, args.episodes, args.length, base / clock)
    out["machine_us_per_node"]["after"] = machine_speed()
    if "real" in out and "lockstep" in out:
        out["speedup"] = round(out["lockstep"]["episodes_per_hour"] / out["real"]["episodes_per_hour"], 2)
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
