"""Dash & Dine: how fast the players harvest, from the episodes' replays.

Upstream's reference scores imply pickers about half as fast as ours (docs/fidelity.md). This prints,
per team of a run, the seconds per target of every harvest call (chat "Harvesting <crop>" to
"Harvested <n> <crop>" of the same player, divided by n, the targets it found, as upstream's chat
counts them), the sweet berry bushes picked per episode and the berries per pick (vanilla: 1–2 at
age 2, 2–3 at age 3, so the mean tells at what age the bushes were picked).

    python benchmarks/harvest_pace.py runs/dd_stems [RUN_DIR ...]
"""

from __future__ import annotations

import argparse
import json
import re
import statistics
from collections import defaultdict
from pathlib import Path

from pillagerbench.replay.read import ReplayError, load_replay

HARVESTING = re.compile(r"Harvesting (\w+)$")
HARVESTED = re.compile(r"Harvested (\d+) (\w+)$")


def team_of(header: dict) -> dict[str, str]:
    """player -> the team (opponent) it plays for."""
    return {p: side["team"] for side in header["sides"].values() for p in side["players"]}


def pace(episode: Path, out: dict) -> None:
    replay = load_replay(episode)
    teams = team_of(replay.header)
    started: dict[tuple[str, str], float] = {}
    picks = defaultdict(list)
    for r in replay.records:
        e = r.get("event") if r.get("type") == "event" else None
        if not e or e.get("player") not in teams:
            continue
        team = teams[e["player"]]
        if e.get("event") == "berries_harvested":
            picks[team].append(e["count"])
        elif e.get("event") == "chat" and (m := HARVESTING.match(e["message"])):
            started[(e["player"], m[1])] = r["t"]
        elif e.get("event") == "chat" and (m := HARVESTED.match(e["message"])):
            t0 = started.pop((e["player"], m[2]), None)
            if t0 is not None and int(m[1]) > 0:
                out[team]["per_target"][m[2]].append((r["t"] - t0) / int(m[1]))
    for team in set(teams.values()):
        out[team]["episodes"] += 1
        out[team]["picks"].extend(picks[team])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", type=Path, nargs="+")
    args = ap.parse_args()
    out: dict = defaultdict(lambda: {"episodes": 0, "picks": [], "per_target": defaultdict(list)})
    for run in args.runs:
        for episode in sorted(p.parent for p in run.glob("**/episode.json")):
            try:
                pace(episode, out)
            except ReplayError as exc:
                print(f"skipped: {exc}")
    for team, d in sorted(out.items()):
        row = {"team": team, "episodes": d["episodes"]}
        if d["picks"]:
            row["bushes_picked_per_episode"] = round(len(d["picks"]) / d["episodes"], 1)
            row["berries_per_pick"] = round(statistics.mean(d["picks"]), 2)
        row["s_per_target"] = {
            crop: round(statistics.mean(v), 2) for crop, v in sorted(d["per_target"].items()) if len(v) >= 3
        }
        print(json.dumps(row))


if __name__ == "__main__":
    main()
