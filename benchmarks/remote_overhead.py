"""Overhead of the remote-team protocol on loopback, printed as JSON.

    python benchmarks/remote_overhead.py [--calls 200] [--stream-s 30]

- pregame_ms: one `POST /pregame` with four players' observations (about the size of a real
  Mushroom War observation), serialisation and parsing included (target: median <= 5 ms).
- events_cpu_pct: the benchmark side's CPU while streaming events as a remote team's players make
  them (2 players, `--events-per-s` events each, one batch a second), as % of one core (target <= 2 %).
The team server is examples/remote_team.py in its own process, so its work is not counted.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

from pillagerbench.teams.remote import wire as P
from pillagerbench.teams.remote.team import call

ROOT = Path(__file__).resolve().parents[1]


def observation(i: int) -> dict:
    """An observation shaped like the bot's (js/bot/observe.js), about 4 KB of JSON."""
    return {
        "position": {"x": 3.5 + i, "y": 4.0, "z": -7.5},
        "health": 20,
        "food": 20,
        "inventory": {"red_mushroom": 3, "oak_planks": 12, "stone_pickaxe": 1},
        "equipment": [None, None, None, None, "stone_pickaxe", None],
        "nearbyBlocks": [f"block_{k}" for k in range(40)],
        "nearbyEntities": {f"entity_{k}": 4.2 + k for k in range(12)},
        "blockRecords": [[k, 4, -k, "red_mushroom_block"] for k in range(60)],
        "chests": {},
        "time": 6000,
        "biome": "plains",
    }


def pregame() -> P.PregameRequest:
    players = [P.PlayerInfo(name=n, spawn=[0.5, 4, 0.5]) for n in ("Ryn", "Raze")]
    return P.PregameRequest(
        episode=0,
        episode_length_s=120,
        scenario=P.ScenarioInfo(key="mushroom_war", title="Mushroom War", description="x" * 3000),
        side=P.SideInfo(
            key="red",
            team_name="red_team",
            players=players,
            opponent_team_name="blue_team",
            opponent_players=["Vex", "Kira"],
        ),
        primitives=["mineBlock", "placeItem", "killMob", "giveToPlayer"],
        primitives_docs="d" * 12000,
        observations={n: observation(i) for i, n in enumerate(("Ryn", "Raze", "Vex", "Kira"))},
        last_episode=None,
    )


async def measure(url: str, calls: int, stream_s: float, per_s: int) -> dict:
    message = pregame()
    for _ in range(20):  # warm-up
        await call(url, "/pregame", message, P.Programs, timeout=5)
    times = []
    for _ in range(calls):
        t0 = time.perf_counter()
        await call(url, "/pregame", message, P.Programs, timeout=5)
        times.append((time.perf_counter() - t0) * 1000)
    event = ["chat", {"username": "Ryn", "message": "Harvesting red_mushroom_block in the red area"}]
    cpu0, wall0 = time.process_time(), time.perf_counter()
    t = 0.0
    while t < stream_s:
        await asyncio.sleep(1.0)
        t = time.perf_counter() - wall0
        batch = {n: [event] * per_s for n in ("Ryn", "Raze")}
        await call(
            url, "/events", P.EventsRequest(episode=0, t=t, time_left_s=120 - t, events=batch), P.Programs, timeout=5
        )
    cpu = time.process_time() - cpu0
    wall = time.perf_counter() - wall0
    return {
        "pregame_bytes": len(message.model_dump_json()),
        "pregame_ms_median": round(statistics.median(times), 3),
        "pregame_ms_p95": round(sorted(times)[int(0.95 * len(times))], 3),
        "events_per_s_per_player": per_s,
        "events_cpu_pct": round(100 * cpu / wall, 3),
    }


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--calls", type=int, default=200)
    p.add_argument("--stream-s", type=float, default=30.0)
    p.add_argument("--events-per-s", type=int, default=20)
    a = p.parse_args()
    server = subprocess.Popen(
        [sys.executable, str(ROOT / "examples" / "remote_team.py"), "0"], stdout=subprocess.PIPE, text=True
    )
    try:
        url = server.stdout.readline().strip().rsplit(" ", 1)[-1]
        result = asyncio.run(measure(url, a.calls, a.stream_s, a.events_per_s))
    finally:
        server.terminate()
    print(json.dumps(result, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
