"""Arena server benchmark (issue "The arena"): prints JSON.

- start-to-ready time (median of several starts)
- idle CPU (% of one core) and RSS of the server process
- CPU and RSS with 6 real bots working (pathing, digging, placing, chatting), and ticks per second held

    python benchmarks/arena_server.py [--bots 6] [--seconds 30]
Targets on a 2-core machine: ready <= 3 s, <= 25 % of one core with 6 active bots, 20 TPS.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import sys
import time
from pathlib import Path

import psutil

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from pillagerbench.server import ArenaServer
from tests.support.bots import TestBot

WORK = """
const { GoalNear } = goals
const home = bot.entity.position.floored()
const end = Date.now() + %d
let i = 0
while (Date.now() < end) {
  const x = home.x + Math.floor(Math.random() * 12) - 6, z = home.z + Math.floor(Math.random() * 12) - 6
  try { await bot.pathfinder.goto(new GoalNear(x, 4, z, 1)) } catch (e) {}
  const below = bot.blockAt(bot.entity.position.offset(1, -1, 0).floored())
  const spot = bot.blockAt(bot.entity.position.offset(1, 0, 0).floored())
  if (spot && spot.name === 'air' && below && below.name !== 'air') {
    try { await bot.equip(mcData.itemsByName.dirt.id, 'hand'); await bot.placeBlock(below, new Vec3(0, 1, 0)); await bot.dig(bot.blockAt(spot.position)) } catch (e) {}
  }
  bot.chat('working ' + (i++))
  await sleep(100)
}
return i
"""


async def measure(proc: psutil.Process, seconds: float) -> tuple[float, float]:
    t0, c0 = time.monotonic(), sum(proc.cpu_times()[:2])
    await asyncio.sleep(seconds)
    cpu = (sum(proc.cpu_times()[:2]) - c0) / (time.monotonic() - t0) * 100
    return cpu, proc.memory_info().rss / 2**20


async def tps(server: ArenaServer, seconds: float) -> float:
    t0, k0 = time.monotonic(), (await server.status())["tick"]
    await asyncio.sleep(seconds)
    return ((await server.status())["tick"] - k0) / (time.monotonic() - t0)


async def main(n_bots: int, seconds: float) -> dict:
    starts = []
    for _ in range(5):
        s = ArenaServer()
        await s.start()
        starts.append(s.ready_seconds)
        await s.stop()
    out = {"ready_s_median": round(statistics.median(starts), 3), "ready_s_max": round(max(starts), 3)}
    server = ArenaServer()
    await server.start()
    proc = psutil.Process(server.process.pid)
    await asyncio.sleep(2)
    out["idle_cpu_pct_one_core"], out["idle_rss_mb"] = [round(v, 1) for v in await measure(proc, 10)]
    bots = []
    for i in range(n_bots):
        bots.append(await TestBot(server.port, f"worker{i}").start())
    for i, b in enumerate(bots):
        await server.set_inventory(b.username, {"dirt": 64})
        await server.teleport(b.username, [40 * i + 0.5, 4, 0.5])
    await asyncio.sleep(2)
    work = [asyncio.create_task(b.eval(WORK % int(seconds * 1000), timeout=seconds + 60)) for b in bots]
    await asyncio.sleep(2)
    (cpu, rss), held = await asyncio.gather(measure(proc, seconds - 4), tps(server, seconds - 4))
    loops = await asyncio.gather(*work)
    out.update(
        {
            "bots": n_bots,
            "busy_cpu_pct_one_core": round(cpu, 1),
            "busy_rss_mb": round(rss, 1),
            "tps_held": round(held, 2),
            "bot_work_loops": sum(loops),
            "kicked": sum(b.kicked for b in bots),
        }
    )
    for b in bots:
        await b.stop()
    await server.stop()
    return out


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--bots", type=int, default=6)
    ap.add_argument("--seconds", type=float, default=30)
    a = ap.parse_args()
    print(json.dumps(asyncio.run(main(a.bots, a.seconds)), indent=2))
