"""Benchmark of the player runtime (issue 3): latency of run() and stop(), memory and CPU of bots.

    python benchmarks/players_bench.py [--bots 4] [--seconds 10] [--repeats 20]

Figures, against the targets:
- run() -> first primitive acting: time from calling run() until the event of the code's first
  call comes back to Python (`bot.save`, a whole round trip through the sandbox), and until the
  chat of a first `sendSignal` comes back from the server (one more server round trip). Target <= 50 ms.
- stop() settling: from stop() until the pending run() has returned, while the bot walks
  (pathfinder) or mines (mineBlock). Target <= 200 ms.
- RSS per bot process after logging in and after the busy phase. Target <= 150 MB.
- CPU of N idle bots and N busy bots (walking back and forth, chatting), % of one core per bot.
  Target <= 10 % per idle bot.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import time

import psutil

from pillagerbench.players import Player
from pillagerbench.server import ArenaServer


def pct(values: list[float], q: float) -> float:
    values = sorted(values)
    return values[min(len(values) - 1, int(round(q * (len(values) - 1))))]


def summary(ms: list[float]) -> dict:
    return {
        "median_ms": round(statistics.median(ms), 1),
        "p90_ms": round(pct(ms, 0.9), 1),
        "max_ms": round(max(ms), 1),
        "n": len(ms),
    }


async def first_event_latency(player: Player, code: str, kind: str, match: str, repeats: int) -> list[float]:
    out = []
    for _ in range(repeats):
        seen: dict[str, float] = {}

        def on_event(e, seen=seen):
            if e[0] == kind and match in str(e[1].get(kind)) and "t" not in seen:
                seen["t"] = time.perf_counter()

        t0 = time.perf_counter()
        await player.run(code, on_event=on_event)
        out.append((seen["t"] - t0) * 1000)
    return out


async def stop_latency(player: Player, code: str, repeats: int, after: float = 0.7) -> list[float]:
    out = []
    for _ in range(repeats):
        task = asyncio.create_task(player.run(code))
        await asyncio.sleep(after)
        t0 = time.perf_counter()
        await player.stop()
        await task
        out.append((time.perf_counter() - t0) * 1000)
    return out


def cpu_seconds(procs: list[psutil.Process]) -> float:
    total = 0.0
    for p in procs:
        t = p.cpu_times()
        total += t.user + t.system + t.children_user + t.children_system
    return total


async def measure_cpu(procs: list[psutil.Process], seconds: float) -> float:
    """% of one core per process, averaged."""
    c0, t0 = cpu_seconds(procs), time.perf_counter()
    await asyncio.sleep(seconds)
    c1, t1 = cpu_seconds(procs), time.perf_counter()
    return 100 * (c1 - c0) / (t1 - t0) / len(procs)


async def main(n_bots: int, seconds: float, repeats: int) -> dict:
    results: dict = {}
    async with ArenaServer(crop_growth_chance=0.0) as server:
        players = [Player(f"Bench{i}", server.port, server=server) for i in range(n_bots)]
        t0 = time.perf_counter()
        for p in players:
            await p.start()
        results["login_s_total"] = round(time.perf_counter() - t0, 2)
        for i, p in enumerate(players):
            await p.reset(position=(i * 40, 4, 0), inventory={})
        p0 = players[0]
        # warm up
        await p0.run("bot.save('warm')")
        results["run_to_first_call_event"] = summary(
            await first_event_latency(p0, "bot.save('go')", "onSave", "go", repeats)
        )
        results["run_to_first_primitive_chat"] = summary(
            await first_event_latency(p0, "await sendSignal(bot, 'Nobody')", "onChat", "[Nobody signal]", repeats)
        )
        results["stop_while_walking"] = summary(
            await stop_latency(
                p0, "await bot.pathfinder.goto(new GoalNear(bot.entity.position.x + 200, 4, 0, 1))", repeats
            )
        )
        await server.fill([3, 4, -3], [20, 4, 3], "slime_block")
        await p0.reset(position=(0, 4, 0))
        results["stop_while_mining"] = summary(
            await stop_latency(p0, "await mineBlock(bot, 'slime_block', 100)", max(3, repeats // 4), after=1.5)
        )
        await server.fill([3, 4, -3], [20, 4, 3], "air")

        procs = [psutil.Process(p.bot.proc.pid) for p in players]
        for i, p in enumerate(players):
            await p.reset(position=(i * 40, 4, 0), inventory={})
        await asyncio.sleep(1)
        results["rss_mb_idle"] = [round(p.memory_info().rss / 2**20, 1) for p in procs]
        results["cpu_pct_per_idle_bot"] = round(await measure_cpu(procs, seconds), 2)

        busy = (
            "const x0 = bot.entity.position.x\n"
            "for (let i = 0; ; i++) {\n"
            "  await bot.pathfinder.goto(new GoalNear(x0 + (i % 2 ? 0 : 12), 4, (i % 3) * 3, 0))\n"
            "  if (i % 4 === 0) bot.chat('lap ' + i)\n"
            "}"
        )
        runs = [asyncio.create_task(p.run(busy)) for p in players]
        await asyncio.sleep(1)
        results["cpu_pct_per_busy_bot"] = round(await measure_cpu(procs, seconds), 2)
        server_proc = psutil.Process(server.process.pid)
        results["server_rss_mb"] = round(server_proc.memory_info().rss / 2**20, 1)
        for p in players:
            await p.stop()
        await asyncio.gather(*runs)
        results["rss_mb_after_busy"] = [round(p.memory_info().rss / 2**20, 1) for p in procs]
        for p in players:
            await p.close()
    results["targets"] = {
        "run_to_first_call_event.median_ms": "<= 50",
        "stop.max_ms": "<= 200",
        "rss_mb": "<= 150",
        "cpu_pct_per_idle_bot": "<= 10",
    }
    return results


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bots", type=int, default=4)
    ap.add_argument("--seconds", type=float, default=10)
    ap.add_argument("--repeats", type=int, default=20)
    args = ap.parse_args()
    print(json.dumps(asyncio.run(main(args.bots, args.seconds, args.repeats)), indent=2))
