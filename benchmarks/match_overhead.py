"""Match benchmark (issue "Scenarios"): prints JSON.

- per-episode overhead: wall time of a series of N episodes minus N x episode_length, per episode
  (target <= 3 s), split into arena+player reset and the rest
- CPU of one match (server, bots, Python) as a share of the whole machine

    python benchmarks/match_overhead.py [--scenario mushroom_war] [--red passive] [--blue balanced] [--episodes 3] [--length 20]
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
from pillagerbench.match import Match
from pillagerbench.scenarios import make_scenario
from pillagerbench.server import ArenaServer
from pillagerbench.teams import make_team


def cpu_seconds(me: psutil.Process) -> float:
    total = sum(me.cpu_times()[:2])
    for child in me.children(recursive=True):
        try:
            total += sum(child.cpu_times()[:2])
        except psutil.NoSuchProcess:
            pass
    return total


async def main(a) -> dict:
    sc = make_scenario(a.scenario, crop_growth_chance=0.3 if a.scenario == "dash_and_dine" else 0.0)
    teams = {"red": make_team(a.red, sc.key), "blue": make_team(a.blue, sc.key)}
    run_dir = Path(tempfile.mkdtemp(prefix="pb-bench-match-"))
    me = psutil.Process()
    async with ArenaServer(log_path=run_dir / "server.log") as server:
        match = Match(server, sc, teams, run_dir, episode_length=a.length, seed=0)
        await match.setup()
        c0, t0 = cpu_seconds(me), time.monotonic()
        recs = [await match.play_episode(i) for i in range(a.episodes)]
        wall, cpu = time.monotonic() - t0, cpu_seconds(me) - c0
        await match.close()
    return {
        "scenario": a.scenario,
        "red": a.red,
        "blue": a.blue,
        "episodes": a.episodes,
        "episode_length_s": a.length,
        "overhead_s_per_episode": round((wall - a.episodes * a.length) / a.episodes, 2),
        "reset_s_per_episode": round(sum(r.reset_s for r in recs) / len(recs), 2),
        "cpu_share_of_machine_pct": round(100 * cpu / wall / psutil.cpu_count(), 1),
        "cpu_cores_used": round(cpu / wall, 2),
        "scores": [(r.red_score, r.blue_score, r.status) for r in recs],
    }


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--scenario", default="mushroom_war")
    ap.add_argument("--red", default="passive")
    ap.add_argument("--blue", default="balanced")
    ap.add_argument("--episodes", type=int, default=3)
    ap.add_argument("--length", type=float, default=20)
    print(json.dumps(asyncio.run(main(ap.parse_args())), indent=1))
