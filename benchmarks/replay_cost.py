"""Replay recording benchmark (issue 15): prints JSON.

- cost: CPU (% of one core) of the server process plus this process while a Recorder records
  the Mushroom War arena with 4 logged-in players, minus the same span without it (differential,
  so the players' and server's own work cancel out); the same for a live-view spectator when
  `--watch` is given
- size: the bytes of a real recording, scaled to a 120 s episode, with `--run-dir` pointing at an
  episode directory that has one (e.g. from `pillagerbench run ... episode_length=120`)

    python benchmarks/replay_cost.py [--seconds 60] [--run-dir RUN/episode_000]
Targets: recording <= 3 % of one core, <= 2 MB per 120 s episode.
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

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from pillagerbench.arena import ArenaServer
from pillagerbench.replay.load import load_replay
from pillagerbench.replay.record import RECORDING, Recorder
from pillagerbench.scenarios import make_scenario
from tests.support.bots import TestBot


def cpu_seconds(procs: list[psutil.Process]) -> float:
    total = 0.0
    for p in procs:
        t = p.cpu_times()
        total += t.user + t.system
    return total


async def span(procs: list[psutil.Process], seconds: float) -> float:
    """% of one core used by `procs` over `seconds` of wall time."""
    c0, w0 = cpu_seconds(procs), time.monotonic()
    await asyncio.sleep(seconds)
    return 100 * (cpu_seconds(procs) - c0) / (time.monotonic() - w0)


async def measure(seconds: float) -> dict:
    sc = make_scenario("mushroom_war")
    async with ArenaServer() as server:
        await sc.arena.build(server)
        bots = []
        for p in sc.all_players():
            bots.append(await TestBot(server.port, p.name).start())
            await asyncio.sleep(0.3)
        try:
            procs = [psutil.Process(server.process.pid), psutil.Process()]
            await asyncio.sleep(3)
            base = await span(procs, seconds)
            out = Path(tempfile.mkdtemp(prefix="pb-replay-bench-")) / RECORDING
            rec = Recorder(server, out, {"scenario": sc.key, "sides": {}}, box=sc.arena.box)
            await rec.start()
            recording = await span(procs, seconds)
            await rec.stop()
            base2 = await span(procs, seconds)
            baseline = (base + base2) / 2
            return {
                "seconds": seconds,
                "baseline_cpu_pct": round(baseline, 2),
                "recording_cpu_pct": round(recording, 2),
                "recording_cost_pct_of_core": round(recording - baseline, 2),
                "frames": rec.frames,
                "frame_hz": round(rec.frames / seconds, 2),
                "idle_recording_bytes": out.stat().st_size,
            }
        finally:
            for b in bots:
                await b.stop()


def size_of(episode_dir: Path) -> dict:
    replay = load_replay(episode_dir)
    size = (episode_dir / RECORDING).stat().st_size
    return {
        "episode": str(episode_dir),
        "bytes": size,
        "recorded_s": replay.duration,
        "bytes_per_120_s": round(size * 120 / max(replay.duration, 1e-9)),
    }


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--seconds", type=float, default=60)
    p.add_argument("--run-dir", type=Path, default=None)
    a = p.parse_args()
    result = asyncio.run(measure(a.seconds))
    if a.run_dir:
        result["size"] = size_of(a.run_dir)
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
