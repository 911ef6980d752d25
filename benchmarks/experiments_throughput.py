"""Experiment throughput (issue "Experiments at scale"): episodes per hour of built-in teams with
1, 2 and 4 matches in parallel on this machine, and the CPU each setting uses. Prints JSON.

Each setting is an experiment of N Mushroom War series (built-in teams, one arena server each)
run with parallel=N through the experiment runner. CPU is summed over this process and every
server and bot process it starts (sampled every 0.5 s, so processes that end are counted too).

    python benchmarks/experiments_throughput.py [--parallel 1 2 4] [--episodes 2] [--length 30]
"""

from __future__ import annotations

import argparse
import asyncio
import json
import sys
import tempfile
import time
from pathlib import Path

import psutil

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))
from pillagerbench.config.compose import load_config
from pillagerbench.experiments import build_series
from pillagerbench.experiments.runner import local_launcher, run_all

PAIRINGS = {
    1: ("[passive]", "[aggressive]"),
    2: ("[passive]", "[aggressive,slimy]"),
    4: ("[passive,balanced]", "[aggressive,slimy]"),
    8: ("[passive,balanced,slimy,aggressive]", "[aggressive,slimy]"),
}


class CpuMeter:
    """CPU seconds of this process and all its descendants, including ones that have ended."""

    def __init__(self):
        self.me = psutil.Process()
        self.seen: dict[int, float] = {}
        self.base = self._now_total()

    def _now_total(self) -> float:
        procs = [self.me] + self.me.children(recursive=True)
        for p in procs:
            try:
                t = p.cpu_times()
                self.seen[p.pid] = t.user + t.system
            except psutil.Error:
                pass
        return sum(self.seen.values())

    async def run(self) -> None:
        while True:
            self._now_total()
            await asyncio.sleep(0.5)

    def total(self) -> float:
        return self._now_total() - self.base


async def one_setting(n: int, episodes: int, length: float) -> dict:
    red, blue = PAIRINGS[n]
    argv = [
        "experiment=round_robin_mushroom_war",
        f"experiment.red_teams={red}",
        f"experiment.blue_teams={blue}",
        f"experiment.episodes={episodes}",
        f"episode_length={length}",
    ]
    specs = build_series(load_config(argv), argv)
    assert len(specs) == n, (n, len(specs))
    run_dir = Path(tempfile.mkdtemp(prefix=f"pb-bench-exp{n}-"))
    dirs = {s.id: run_dir / "series" / s.id for s in specs}
    meter = CpuMeter()
    psutil.cpu_percent(None)
    sampler = asyncio.create_task(meter.run())
    t0 = time.monotonic()
    results = await run_all(specs, dirs, n, local_launcher(run_dir))
    wall = time.monotonic() - t0
    machine_pct = psutil.cpu_percent(None)
    sampler.cancel()
    cpu = meter.total()
    recs = [json.loads(x) for d in dirs.values() for x in (d / "episodes.jsonl").read_text().splitlines()]
    ok = sum(r["status"] == "ok" for r in recs)
    return {
        "parallel": n,
        "series": n,
        "episodes": len(recs),
        "episodes_ok": ok,
        "episode_length_s": length,
        "wall_s": round(wall, 1),
        "episodes_per_hour": round(len(recs) / wall * 3600, 1),
        "game_time_share": round(len(recs) * length / wall / n, 3),
        "cpu_cores_used": round(cpu / wall, 2),
        "cpu_share_of_machine_pct": round(100 * cpu / wall / psutil.cpu_count(), 1),
        "machine_cpu_busy_pct": machine_pct,
        "errors": [r for r in results.values() if r["status"] != "done"],
    }


async def main(a) -> dict:
    out = {"cpu_count": psutil.cpu_count(), "results": []}
    for n in a.parallel:
        out["results"].append(await one_setting(n, a.episodes, a.length))
        print(json.dumps(out["results"][-1]), file=sys.stderr, flush=True)
    return out


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--parallel", type=int, nargs="+", default=[1, 2, 4], choices=sorted(PAIRINGS))
    ap.add_argument("--episodes", type=int, default=2)
    ap.add_argument("--length", type=float, default=30.0)
    print(json.dumps(asyncio.run(main(ap.parse_args())), indent=1))
