"""The built-in opponents on generated layouts (issue 29, item 5): each opponent against do_nothing
(the opponent blue, as upstream measured), on the paper's layout and on dev seeds; its mean score on
each, the ratio (target: at least 0.5), actions the server refused (target: none), episodes played
under lag, and the players' longest still stretches (benchmarks/idle_players.py).

    python benchmarks/layout_opponents.py OUT_DIR [--seeds 5] [--paper 1] [--length 60] [--only NAME ...]

Each opponent plays `--paper` episodes on the paper's layout and one episode on each of `--seeds`
dev seeds (split=dev: seeds drawn from the episodes' seeds, the same on every run). Opponents that
need longer to serve their first food play longer (LENGTH). Prints one JSON line per opponent.
Measure on an otherwise idle machine: bots act in real time.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from idle_players import still_stretches

from pillagerbench.match import Match
from pillagerbench.rundir import RunDir
from pillagerbench.scenarios import make_scenario
from pillagerbench.server import ArenaServer
from pillagerbench.teams import TEAMS, make_team

OPPONENTS = {name: cls.scenarios[0] for name, cls in TEAMS.items() if cls.scenarios}
# first food served at 57-63 s (potato_cookie) and 51-63 s (cake_beetroot): docs/fidelity.md
LENGTH = {"potato_cookie": 120, "cake_beetroot": 90}


async def series(opponent: str, out: Path, episodes: int, split: str | None, length: float) -> list[dict]:
    sc = make_scenario(OPPONENTS[opponent])
    teams = {"red": make_team("do_nothing", sc.key), "blue": make_team(opponent, sc.key)}
    out.mkdir(parents=True, exist_ok=True)
    async with ArenaServer(log_path=out / "server.log") as server:
        match = Match(server, sc, teams, out, episode_length=length, seed=7, split=split)
        try:
            await match.setup()
            await match.play_episodes(range(episodes), RunDir(out).append)
        finally:
            await match.close()
    return [rec for _, rec in sorted(RunDir(out).read()[0].items())]


def summary(opponent: str, paper: list[dict], dev: list[dict], out: Path) -> dict:
    def mean(recs):
        scores = [r["blue_score"] for r in recs if r["status"] == "ok"]
        return round(statistics.fmean(scores), 2) if scores else None

    still = [s for r in out.glob("*/episode_*/replay.jsonl.gz") for s in still_stretches(r, 20)]
    p, d = mean(paper), mean(dev)
    return {
        "opponent": opponent,
        "paper": p,
        "dev": d,
        "ratio": round(d / p, 2) if p and d is not None else None,
        "dev_scores": {str(r["layout"]): r["blue_score"] for r in dev},
        "refusals": sum(sum(r.get("refusals", {}).values()) for r in paper + dev),
        "failed": sum(r["status"] != "ok" for r in paper + dev),
        "lagged": sum(bool(r.get("lagged")) for r in paper + dev),
        "still_20s": [(s["player"], s["still_s"]) for s in still],
    }


async def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=Path)
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--paper", type=int, default=1)
    ap.add_argument("--length", type=float, default=60)
    ap.add_argument("--only", nargs="*", default=None)
    args = ap.parse_args()
    for opponent in args.only or OPPONENTS:
        length = max(args.length, LENGTH.get(opponent, 0))
        base = args.out / opponent
        paper = await series(opponent, base / "paper", args.paper, None, length) if args.paper else []
        dev = await series(opponent, base / "dev", args.seeds, "dev", length)
        print(json.dumps(summary(opponent, paper, dev, base)), flush=True)


if __name__ == "__main__":
    asyncio.run(main())
