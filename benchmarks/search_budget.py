"""How many nodes a path search visits per tick, on either clock: the fidelity experiment (every
built-in opponent against do_nothing) with the bots counting the nodes of each search slice that used
its whole tick (PB_TRACE=search, js/bot/search_trace.js). Prints JSON: the median and quartiles over
every such slice, and per bot that searched.

    python benchmarks/search_budget.py [--clock real] [--parallel 4] [--episodes 1] [--keep DIR]

On the real clock a slice is 7 ms of the machine's time (js/bot/main.js), so the figure is the
machine's and its load's: with the defaults it is the condition the suite's reference figures were
measured in (4 matches at once on 2 cores), which the lockstep clock's budget per tick was set from
(js/clock/game_clock.js, READ_COST_MS; docs/clock.md). On the lockstep clock it is fixed: 140.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import tempfile
from pathlib import Path

from lockstep_throughput import play


def slices(run_dir: Path) -> dict[str, list[int]]:
    """series/bot -> the nodes of each full slice its searches had."""
    out: dict[str, list[int]] = {}
    for log in sorted(run_dir.glob("series/*/logs/*.log")):
        for line in log.read_text(errors="replace").splitlines():
            if line.startswith("[search] "):
                full = json.loads(line[len("[search] ") :])["full"]
                if full:
                    out.setdefault(f"{log.parent.parent.name}/{log.stem}", []).extend(full)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--clock", choices=["real", "lockstep"], default="real")
    ap.add_argument("--parallel", type=int, default=4)
    ap.add_argument("--episodes", type=int, default=1, help="per opponent")
    ap.add_argument("--keep", type=Path, help="write the run directory here (default: a temporary directory)")
    args = ap.parse_args()
    run_dir = args.keep or Path(tempfile.mkdtemp(prefix="search-budget-"))
    os.environ["PB_TRACE"] = "search"  # the bots inherit it (host/node.py lets PB_TRACE through)
    run = play(args.clock, args.parallel, args.episodes, 120.0, run_dir)
    per_bot = slices(run_dir)
    pooled = sorted(n for full in per_bot.values() for n in full)
    if not pooled:
        raise SystemExit("no search used a whole tick")
    q1, median, q3 = statistics.quantiles(pooled, n=4)
    print(json.dumps({
        "run": run,
        "full_slices": len(pooled),
        "nodes_per_tick": {"median": median, "q1": q1, "q3": q3},
        "per_bot": {bot: {"slices": len(f), "median": statistics.median(f)} for bot, f in per_bot.items()},
    }, indent=1))  # fmt: skip


if __name__ == "__main__":
    main()
