"""What one built-in match costs (issue 11, "scores must not depend on load"): CPU seconds per
game-second for each kind of process (the bots, the arena server, this Python process), the RSS
of a whole match, and the episodes per hour that cost implies on this machine. Prints JSON.

By default it plays two built-in matches, one after the other, each on its own warm server:
Mushroom War passive (red) vs balanced (blue) and Dash & Dine berries vs potato_cookie, a few
short episodes each (30 s instead of 120 s: the per-second cost is the same, the reset between
episodes weighs a little more). CPU is read from /proc through psutil every 0.5 s, per process,
so it is meaningful on a shared machine even when wall-clock figures are not; the load average
is recorded beside it.

    python benchmarks/match_cost.py [--episodes 2] [--length 30] [--only mushroom_war]
        [--clock lockstep] [--red aggressive --blue do_nothing]

`implied_parallel` is how many such matches fit in HEADROOM of the machine's cores;
`episodes_per_hour` is that many matches playing 120-s episodes with the measured reset overhead.
With `--clock lockstep` a match is not paced by the wall clock, so what bounds episodes per hour is
the CPU a 120-s episode costs: `lockstep_bound.episodes_per_hour` is every core of the machine busy
with such episodes (CPU of play and resets alike, measured between the first episode's start and the
last one's end), and `cpu_ms_per_tick` splits a game tick's CPU by process kind (bots per bot).
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import sys
import tempfile
import time
from pathlib import Path

import psutil

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))
from pillagerbench.config.schema import ClockConfig
from pillagerbench.match import Match
from pillagerbench.scenarios import make_scenario
from pillagerbench.server import ArenaServer
from pillagerbench.server.clock import TICK_S
from pillagerbench.teams import make_team

MATCHES = {
    "mushroom_war": ("passive", "balanced", 0.0),
    "dash_and_dine": ("berries", "potato_cookie", 0.3),
}
HEADROOM = 0.8  # share of the cores matches may use (the rest: the OS, bursts, the runner)
PAPER_LENGTH_S = 120.0


def kind_of(proc: psutil.Process) -> str:
    try:
        cmd = " ".join(proc.cmdline())
    except psutil.Error:
        return "gone"
    if "bot/main.js" in cmd:
        return "bots"
    if "server/main.js" in cmd:
        return "server"
    return "other"


class Meter:
    """CPU seconds and RSS per process kind over this process and every process it starts,
    including processes that end while it watches."""

    def __init__(self) -> None:
        self.me = psutil.Process()
        self.kinds: dict[int, str] = {self.me.pid: "python"}
        self.procs: dict[int, psutil.Process] = {self.me.pid: self.me}
        self.cpu: dict[int, float] = {}
        self.rss_peak: dict[str, float] = {}
        self.base: dict[str, float] = {}

    def sample(self) -> dict[str, float]:
        for child in self.me.children(recursive=True):
            if child.pid not in self.procs:
                self.procs[child.pid] = child
            if self.kinds.get(child.pid, "other") == "other":  # a child seen before its exec reads as Python's
                self.kinds[child.pid] = kind_of(child)
        rss: dict[str, float] = {}
        for pid, p in self.procs.items():
            try:
                with p.oneshot():
                    t = p.cpu_times()
                    self.cpu[pid] = t.user + t.system
                    rss[self.kinds[pid]] = rss.get(self.kinds[pid], 0.0) + p.memory_info().rss / 2**20
            except psutil.Error:
                pass
        for k, v in rss.items():
            self.rss_peak[k] = max(self.rss_peak.get(k, 0.0), v)
        return self.by_kind()

    def by_kind(self) -> dict[str, float]:
        out: dict[str, float] = {}
        for pid, secs in self.cpu.items():
            out[self.kinds[pid]] = out.get(self.kinds[pid], 0.0) + secs
        return out

    def start(self) -> None:
        self.base = self.sample()
        self.rss_peak = {}

    def since_start(self) -> dict[str, float]:
        now = self.sample()
        return {k: v - self.base.get(k, 0.0) for k, v in now.items()}

    async def watch(self) -> None:
        while True:
            self.sample()
            await asyncio.sleep(0.5)


def bench_match(server, sc, teams, run_dir: Path, length: float, clock: str) -> Match:
    """A seed-0 match on `clock`: lockstep unpaced (speed max), the real clock as it comes."""
    pace = "max" if clock == "lockstep" else 1.0
    return Match(server, sc, teams, run_dir, episode_length=length, seed=0, clock=ClockConfig(mode=clock, speed=pace))


async def one_match(scenario: str, episodes: int, length: float, clock: str, pair: tuple[str, str] | None) -> dict:
    red, blue, growth = MATCHES[scenario]
    if pair:
        red, blue = pair
    sc = make_scenario(scenario, crop_growth_chance=growth or 0.0)
    teams = {"red": make_team(red, sc.key), "blue": make_team(blue, sc.key)}
    run_dir = Path(tempfile.mkdtemp(prefix="pb-match-cost-"))
    meter = Meter()
    watcher = asyncio.create_task(meter.watch())
    try:
        async with ArenaServer(log_path=run_dir / "server.log", clock=clock) as server:
            match = bench_match(server, sc, teams, run_dir, length, clock)
            await match.setup()
            bots = len(match.players)
            meter.start()
            load_before, t0 = os.getloadavg(), time.monotonic()
            recs = [await match.play_episode(i) for i in range(episodes)]
            wall = time.monotonic() - t0
            cpu = meter.since_start()
            rss = dict(meter.rss_peak)
            await match.close()
    finally:
        watcher.cancel()
    game_s = episodes * length
    per_game_s = {k: round(cpu.get(k, 0.0) / game_s, 4) for k in ("bots", "server", "python")}
    cores = sum(per_game_s.values())
    overhead = max(0.0, wall / episodes - length)
    ticks = game_s / TICK_S
    per_tick = {k: round(cpu.get(k, 0.0) * 1000 / ticks, 3) for k in ("server", "python")}
    per_tick["bot"] = round(cpu.get("bots", 0.0) * 1000 / ticks / max(1, bots), 3)
    return {
        "scenario": scenario,
        "clock": clock,
        "red": red,
        "blue": blue,
        "episodes": episodes,
        "episode_length_s": length,
        "wall_s": round(wall, 1),
        "overhead_s_per_episode": round(overhead, 2),
        "cpu_s_per_game_s": per_game_s,
        "cores_per_match": round(cores, 3),
        "bots": bots,
        "cpu_ms_per_tick": per_tick,
        "cpu_s_per_episode": round(sum(cpu.get(k, 0.0) for k in ("bots", "server", "python")) / episodes, 2),
        "rss_mb_per_match": {k: round(rss.get(k, 0.0)) for k in ("bots", "server", "python")},
        "rss_mb_total": round(sum(rss.get(k, 0.0) for k in ("bots", "server", "python"))),
        "load_avg_before": [round(x, 2) for x in load_before],
        "load_avg_after": [round(x, 2) for x in os.getloadavg()],
        "episodes_status": [r.status for r in recs],
        "scores": [(r.red_score, r.blue_score) for r in recs],
        "server_tps": [r.server_tps for r in recs],
        "lagged": [getattr(r, "lagged", None) for r in recs],
    }


def implied(cores_per_match: float, overhead_s: float) -> dict:
    cpus = psutil.cpu_count() or 1
    parallel = max(1, int(cpus * HEADROOM / cores_per_match)) if cores_per_match > 0 else cpus
    per_match = 3600.0 / (PAPER_LENGTH_S + overhead_s)
    return {
        "cpus": cpus,
        "headroom": HEADROOM,
        "implied_parallel": parallel,
        "episodes_per_hour": round(parallel * per_match, 1),
    }


def lockstep_bound(cpu_s_per_episode: float, length: float) -> dict:
    """Episodes per hour with every core busy, scaled to 120-s episodes (the reset's CPU scaled too:
    an upper bound on what parallel lockstep matches can reach on this machine)."""
    cpus = psutil.cpu_count() or 1
    per_paper_episode = cpu_s_per_episode * PAPER_LENGTH_S / length
    return {"cpus": cpus, "cpu_s_per_120s_episode": round(per_paper_episode, 1),
            "episodes_per_hour": round(cpus * 3600.0 / per_paper_episode, 1)}  # fmt: skip


async def main(a) -> dict:
    pair = (a.red, a.blue) if a.red else None
    results = [await one_match(s, a.episodes, a.length, a.clock, pair) for s in (a.only or list(MATCHES))]
    worst = max(r["cores_per_match"] for r in results)
    overhead = max(r["overhead_s_per_episode"] for r in results)
    bound = {} if a.clock == "real" else {
        "lockstep_bound": lockstep_bound(max(r["cpu_s_per_episode"] for r in results), a.length)
    }  # fmt: skip
    return {
        "matches": results,
        "worst_cores_per_match": worst,
        "worst_rss_mb_per_match": max(r["rss_mb_total"] for r in results),
        **implied(worst, overhead),
        **bound,
    }


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--episodes", type=int, default=2)
    ap.add_argument("--length", type=float, default=30)
    ap.add_argument("--only", nargs="*", choices=list(MATCHES))
    ap.add_argument("--clock", choices=["real", "lockstep"], default="real")
    ap.add_argument("--red", help="the red team (with --blue): instead of the scenario's default pair")
    ap.add_argument("--blue")
    args = ap.parse_args()
    if bool(args.red) != bool(args.blue):
        ap.error("--red and --blue go together")
    print(json.dumps(asyncio.run(main(args)), indent=1))
