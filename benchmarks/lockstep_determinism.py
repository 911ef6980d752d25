"""Same seed, same episode? (issue "Game time, not wall time", item 4): play one seeded lockstep episode
of built-in teams several times and compare them: the score timelines, and the replay frames (every
player's position and look at each frame, from the game's first frame on). Prints JSON.

    python benchmarks/lockstep_determinism.py [--repeats 5] [--length 60] [--seed 3] [--load] [--ticks]
        [--episodes 1] [red=TEAM blue=TEAM scoring=upstream ...]

`--episodes N` plays N episodes in each repeat (one plain run, the series' episodes one after the
other on one server, as an experiment plays them) and compares each episode with the same episode of
the first repeat: what one episode leaves behind must not move the next.

`--load` plays a second match (real clock) beside each repeat, loading the machine. `--ticks` has each
bot write where it is after every tick (PB_TRACE=ticks, js/bot/lockstep.js) and says, per bot, the
first tick at which a repeat parts from the first, and how.
"""

from __future__ import annotations

import argparse
import gzip
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CLI = [sys.executable, "-m", "pillagerbench.cli", "run", "display=plain"]


def recorded(episode: Path) -> list[dict]:
    path = episode / "replay.jsonl.gz"
    return [r for r in (json.loads(line) for line in gzip.open(path)) if r.get("type") == "frame"]


def frames(found: list[dict]) -> list[dict]:
    first = found[0]["tick"] if found else 0
    return [{"tick": f["tick"] - first, "players": f.get("players")} for f in found]


def play(run: Path, args: argparse.Namespace) -> list[dict]:
    cmd = [*CLI, "clock=lockstep", f"seed={args.seed}", f"episode_length={args.length}", f"run_dir={run}",
           f"episodes={args.episodes}", *args.teams]  # fmt: skip
    load = None
    if args.load:
        load = subprocess.Popen(
            [*CLI, "episode_length=60", f"episodes={args.episodes}", f"run_dir={run}-load"],
            cwd=ROOT,
            stdout=subprocess.DEVNULL,
        )
    env = {**os.environ, "PB_TRACE": "ticks"} if args.ticks else None
    subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, env=env)
    if load is not None:
        load.wait()
    return [episode(run, i, args.ticks) for i in range(args.episodes)]


def episode(run: Path, index: int, traced: bool) -> dict:
    ep = run / f"episode_{index:03d}"
    timeline = json.loads((ep / "timeline.json").read_text())
    found = recorded(ep)
    start = found[0]["tick"] if found else 0
    lines = (ep / "world_events.jsonl").read_text().splitlines()
    events = [line for line in lines if not json.loads(line).get("after_whistle")]  # the game's, not the stop's
    return {
        "timeline": timeline,
        "events": events,
        "frames": frames(found),
        "ticks": ticks(run, start) if traced and index == 0 else {},
    }


def ticks(run: Path, start: int) -> dict[str, dict[int, str]]:
    """Each bot's state after each tick of the game (counted from its first frame), from its log."""
    found: dict[str, dict[int, str]] = {}
    for log in sorted((run / "logs").glob("*.log")):
        lines = (x.split(" ", 2) for x in log.read_text().splitlines() if x.startswith("[tick] "))
        found[log.stem] = {int(t) - start: rest for _, t, rest in lines if int(t) >= start}
    return found


def first_parting(a: dict[int, str], b: dict[int, str]) -> list | None:
    """The first tick of the game at which two traces of one bot differ, and both states."""
    state = lambda line: (line or "").split(" p", 1)[0]  # noqa: E731 (the packets seen may differ: update_time)
    for t in sorted(a):
        if state(a[t]) != state(b.get(t)):
            return [t, *(x.get(y) for x in (a, b) for y in (t - 1, t))]
    return None


def first_difference(a: list[dict], b: list[dict]) -> float | None:
    """Game seconds to the first replay frame that differs (None: none does)."""
    for x, y in zip(a, b):
        if x != y:
            return round(x["tick"] * 0.05, 2)
    return None


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--length", type=float, default=60.0)
    ap.add_argument("--seed", type=int, default=3)
    ap.add_argument("--load", action="store_true")
    ap.add_argument("--ticks", action="store_true", help="(first episode only)")
    ap.add_argument("--episodes", type=int, default=1)
    ap.add_argument("teams", nargs="*", help="e.g. red=do_nothing blue=aggressive (default: the run's own)")
    args = ap.parse_args()
    base = Path(tempfile.mkdtemp(prefix="lockstep-determinism-"))
    repeats = [play(base / f"r{i}", args) for i in range(args.repeats)]
    out = {"repeats": args.repeats, "load": args.load, "episodes": [compare(list(e)) for e in zip(*repeats)]}
    out["runs"] = str(base)
    if args.episodes == 1:  # as before --episodes: the one episode's comparison at the top level
        out = {**{k: v for k, v in out.items() if k != "episodes"}, **out["episodes"][0]}
    print(json.dumps(out, indent=1))


def compare(plays: list[dict]) -> dict:
    """One episode as each repeat played it, against the first repeat's."""
    first = plays[0]
    return {
        "identical_timelines": sum(p["timeline"] == first["timeline"] for p in plays),
        "identical_world_events": sum(p["events"] == first["events"] for p in plays),
        "finals": [p["timeline"][-1] for p in plays],
        "first_frame_difference_s": [first_difference(first["frames"], p["frames"]) for p in plays[1:]],
        "ticks_parted": [
            {bot: first_parting(trace, p["ticks"].get(bot, {})) for bot, trace in first["ticks"].items()}
            for p in plays[1:]
        ],
    }


if __name__ == "__main__":
    main()
