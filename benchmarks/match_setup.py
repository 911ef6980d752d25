"""A match's setup (issue "Game time, not wall time", the suite's time): wall seconds from a running
arena server to every player of a match logged in and spawned (`Match.setup`), the median of --repeats,
each on a fresh server. Prints JSON.

    python benchmarks/match_setup.py [--repeats 5] [--scenario mushroom_war] [--clock lockstep]

Every series, every test that plays a match and every restart after a dead server pays it: the bots'
processes load their libraries, then log in one at a time.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from match_cost import bench_match  # a sibling script

from pillagerbench.scenarios import make_scenario
from pillagerbench.server import ArenaServer
from pillagerbench.teams import make_team


async def one_setup(scenario: str, clock: str) -> float:
    sc = make_scenario(scenario)
    teams = {side: make_team("do_nothing", sc.key) for side in ("red", "blue")}
    run_dir = Path(tempfile.mkdtemp(prefix="pb-bench-setup-"))
    async with ArenaServer(log_path=run_dir / "server.log", clock=clock) as server:
        match = bench_match(server, sc, teams, run_dir, 5, clock)
        started = time.monotonic()
        try:
            await match.setup()
            return time.monotonic() - started
        finally:
            await match.close()


async def main(a) -> dict:
    walls = [await one_setup(a.scenario, a.clock) for _ in range(a.repeats)]
    return {
        "scenario": a.scenario,
        "clock": a.clock,
        "setup_s": [round(w, 2) for w in walls],
        "setup_s_median": round(statistics.median(walls), 2),
    }


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--scenario", default="mushroom_war")
    ap.add_argument("--clock", choices=["real", "lockstep"], default="lockstep")
    print(json.dumps(asyncio.run(main(ap.parse_args())), indent=1))
