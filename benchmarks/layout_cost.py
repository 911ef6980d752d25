"""Layout benchmark (issue 29, "Arenas no one has seen"): prints JSON, each figure as median, min
and max over its samples.

- generating a layout (its validation included: the generator returns only a layout that passes)
  and validating it again alone, per layout, both scenarios (target <= 50 ms)
- building a generated layout's arena on a warm server, each build on another layout than the
  one standing (target <= 2 s), beside rebuilding the same layout
- the reset between two episodes of a match (arena and players, the episode record's `reset_s`)
  with `split=dev`, every episode on a layout of its own (target <= 3 s), beside a match on one
  layout (about 0.3 s before layouts existed); the teams do nothing, episodes are short

    python benchmarks/layout_cost.py [--layouts 200] [--builds 8] [--episodes 6] [--length 2]
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
from pillagerbench.match import Match
from pillagerbench.scenarios import SCENARIOS, make_scenario
from pillagerbench.server import ArenaServer
from pillagerbench.teams import make_team


def spread(seconds: list[float], unit: float = 1.0) -> dict:
    """Median, min and max, in seconds (unit 1) or milliseconds (unit 1000)."""
    return {k: round(f(seconds) * unit, 3) for k, f in (("median", statistics.median), ("min", min), ("max", max))}


def generation(name: str, n: int) -> dict:
    rules = SCENARIOS[name].layouts
    made, checked = [], []
    for seed in range(n):
        t0 = time.perf_counter()
        layout = rules.make(seed)
        t1 = time.perf_counter()
        assert not rules.problems(layout), seed
        made.append(t1 - t0)
        checked.append(time.perf_counter() - t1)
    return {"layouts": n, "generate_and_validate_ms": spread(made, 1000), "validate_alone_ms": spread(checked, 1000)}


async def builds(server: ArenaServer, name: str, n: int) -> dict:
    paper = make_scenario(name)
    await paper.arena.build(server)  # warm: the server has built this scenario's box once
    other, same = [], []
    for seed in range(n):
        arena = paper.with_layout(seed).arena  # generated before the clock starts
        t0 = time.monotonic()
        await arena.build(server)  # over the previous layout's arena
        t1 = time.monotonic()
        await arena.build(server)  # the same layout again: what a reset did before layouts
        other.append(t1 - t0)
        same.append(time.monotonic() - t1)
    return {"builds": n, "build_other_layout_s": spread(other), "build_same_layout_s": spread(same)}


async def resets(server: ArenaServer, name: str, episodes: int, length: float, split: str | None) -> dict:
    sc = make_scenario(name, crop_growth_chance=0.0)
    teams = {side: make_team("do_nothing", name) for side in ("red", "blue")}
    with tempfile.TemporaryDirectory(prefix="pb-bench-layout-") as run_dir:
        match = Match(server, sc, teams, Path(run_dir), episode_length=length, seed=0, split=split)
        try:
            await match.setup()
            recs = [await match.play_episode(i) for i in range(episodes)]
        finally:
            await match.close()
    assert all(r.status == "ok" for r in recs), [r.error for r in recs]
    layouts = {r.layout for r in recs}
    return {"episodes": episodes, "layouts": len(layouts), "reset_s": spread([r.reset_s for r in recs[1:]])}


async def on_server(a) -> dict:
    out: dict = {}
    async with ArenaServer() as server:
        for name in SCENARIOS:
            out[name] = await builds(server, name, a.builds)
            out[name]["reset_other_layouts"] = await resets(server, name, a.episodes, a.length, "dev")
            out[name]["reset_same_layout"] = await resets(server, name, a.episodes, a.length, None)
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--layouts", type=int, default=200, help="layouts generated per scenario")
    ap.add_argument("--builds", type=int, default=8, help="arenas built per scenario")
    ap.add_argument("--episodes", type=int, default=6, help="episodes per match (the first has no reset between)")
    ap.add_argument("--length", type=float, default=2.0, help="seconds per episode")
    ap.add_argument("--no-server", action="store_true", help="only the generation (no server)")
    a = ap.parse_args()
    out = {name: generation(name, a.layouts) for name in SCENARIOS}
    if not a.no_server:
        for name, figures in asyncio.run(on_server(a)).items():
            out[name].update(figures)
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
