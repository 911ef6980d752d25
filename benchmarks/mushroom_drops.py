"""Mushroom War: how many of its own caps each team dug, and how lucky its drops were.

A Mushroom War score is the mushrooms a team holds, and a cap block drops 0, 1 or 2 of them (vanilla's
uniform −6..2 clamped at 0: mean 1/3, standard deviation 2/3). Five episodes of ~60 caps therefore
carry about ±10 % of drop luck on top of what the players did. This prints, per opponent (and side),
the caps its players dug per episode, the mushrooms those caps dropped per cap, and the points the
caps would give at the mean drop (caps / 3): the part of the score that is the players' doing.

    python benchmarks/mushroom_drops.py runs/fid_final [RUN_DIR ...]
"""

from __future__ import annotations

import argparse
import gzip
import json
import statistics
from collections import defaultdict
from pathlib import Path

OWN_CAP = {"red": "red_mushroom_block", "blue": "brown_mushroom_block"}
MEAN_DROP = 1 / 3


def sides(episode: Path) -> dict[str, str]:
    """player -> side, from the replay's header."""
    with gzip.open(episode / "replay.jsonl.gz", "rt") as f:
        header = json.loads(f.readline())
    return {p: side for side, s in header["sides"].items() for p in s["players"]}


def dug(episode: Path) -> dict[str, tuple[int, int]]:
    """side -> (own caps dug by its players, mushrooms they dropped)."""
    side_of = sides(episode)
    out = defaultdict(lambda: [0, 0])
    for line in (episode / "world_events.jsonl").read_text().splitlines():
        e = json.loads(line)
        side = side_of.get(e.get("player"))
        if e.get("event") != "block_dug" or side is None or e.get("block") != OWN_CAP[side]:
            continue
        out[side][0] += 1
        out[side][1] += sum(n for _, n in e.get("drops", []))
    return {k: (v[0], v[1]) for k, v in out.items()}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", help="run directories (experiments) with Mushroom War series")
    args = ap.parse_args()
    per = defaultdict(list)  # (team, side) -> [(caps, drops, score)]
    for run in args.runs:
        for series in sorted(Path(run).glob("series/*mushroom_war*")):
            for line in (series / "episodes.jsonl").read_text().splitlines():
                ep = json.loads(line)
                episode = series / f"episode_{ep['episode']:03d}"
                if ep.get("status") != "ok" or not (episode / "world_events.jsonl").exists():
                    continue
                counts = dug(episode)
                for side in ("red", "blue"):
                    caps, drops = counts.get(side, (0, 0))
                    clean = ep.get("scores", {}).get("clean", {}).get(side, ep[f"{side}_score"])  # held at the end
                    per[(ep[side], side)].append((caps, drops, clean))
    print("| team (side) | episodes | caps dug per episode | mushrooms per cap | points (clean) | caps / 3 |")
    print("|---|---|---|---|---|---|")
    for (team, side), rows in sorted(per.items()):
        caps = [r[0] for r in rows]
        drops = sum(r[1] for r in rows)
        per_cap = drops / sum(caps) if sum(caps) else float("nan")
        points = statistics.mean(r[2] for r in rows)
        print(
            f"| {team} ({side}) | {len(rows)} | {statistics.mean(caps):.1f} | {per_cap:.3f} | {points:.2f} |"
            f" {statistics.mean(caps) * MEAN_DROP:.2f} |"
        )


if __name__ == "__main__":
    main()
