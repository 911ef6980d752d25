"""Replay recording benchmark (issue 15): prints JSON.

- cost: CPU (% of one core) of the server process plus this process while a Recorder records
  the Mushroom War arena with 4 logged-in players, minus the same span without it (differential,
  so the players' and server's own work cancel out); the same for a live-view spectator when
  `--watch` is given
- size: the bytes of a real recording, scaled to a 120 s episode, with `--run-dir` pointing at an
  episode directory that has one (e.g. from `pillagerbench run ... episode_length=120`)

    python benchmarks/replay_cost.py [--seconds 60] [--run-dir RUN/episode_000]
    python benchmarks/replay_cost.py --watch [--seconds 60]     # the live view, with a headless Chromium watching
Targets: recording <= 3 % of one core, <= 2 MB per 120 s episode; the live view <= 10 % of one core
(the server and the view's process; the browser is the watcher's own).
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
from pillagerbench.replay.read import load_replay
from pillagerbench.replay.record import RECORDING, Recorder
from pillagerbench.scenarios import make_scenario
from pillagerbench.server import ArenaServer
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


async def watched_match(seconds: float, watch: bool) -> dict:
    """CPU (% of one core) of the arena server process and its children (the live view) during a
    real match (aggressive vs balanced), with `watch` a live view and a headless Chromium looking at it."""
    import shutil
    import subprocess

    from pillagerbench.match import Match
    from pillagerbench.teams import make_team

    sc = make_scenario("mushroom_war", crop_growth_chance=0.0)
    run = Path(tempfile.mkdtemp(prefix="pb-watch-bench-"))
    browser = None
    async with ArenaServer(log_path=run / "server.log", watch=0 if watch else None) as server:
        teams = {"red": make_team("aggressive", sc.key), "blue": make_team("balanced", sc.key)}
        match = Match(server, sc, teams, run, episode_length=seconds + 10, seed=1)
        try:
            await match.setup()
            if watch:
                exe = shutil.which("chromium") or shutil.which("google-chrome")
                browser = subprocess.Popen(
                    [
                        exe,
                        "--headless",
                        "--no-sandbox",
                        "--use-angle=swiftshader",
                        "--enable-unsafe-swiftshader",
                        f"--user-data-dir={run / 'profile'}",
                        "--remote-debugging-port=0",
                        server.watch_url,
                    ],
                    stdout=subprocess.DEVNULL,
                    stderr=subprocess.DEVNULL,
                )
            episode = asyncio.create_task(match.play_episode(0))
            await asyncio.sleep(5)
            server_proc = psutil.Process(server.process.pid)
            procs = [server_proc, *server_proc.children()]
            cpu = await span(procs, seconds)
            rec = await episode
            return {"watch": watch, "server_and_view_cpu_pct": round(cpu, 2), "server_tps": rec.server_tps}
        finally:
            if browser:
                browser.kill()
                browser.wait()
            await match.close()


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
    p.add_argument("--watch", action="store_true", help="measure the live view instead (two real matches)")
    a = p.parse_args()
    if a.watch:
        without = asyncio.run(watched_match(a.seconds, False))
        with_view = asyncio.run(watched_match(a.seconds, True))
        cost = round(with_view["server_and_view_cpu_pct"] - without["server_and_view_cpu_pct"], 2)
        print(json.dumps({"without": without, "with_view": with_view, "live_view_cost_pct_of_core": cost}, indent=1))
        return
    result = asyncio.run(measure(a.seconds))
    if a.run_dir:
        result["size"] = size_of(a.run_dir)
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
