"""Players that stood still while their code ran: a stalled primitive (a walk or a window that never
ends) shows as a long stretch without a move or a chat in the episode's replay. Built-in opponents
keep moving all episode, so a stretch of 20 s or more is worth a look.

Reads every episode of a run directory (replay.jsonl.gz: frames at 5 Hz, chat, program start/end)
and prints, as JSON lines, each player's longest still stretch of at least --min seconds.

    python benchmarks/idle_players.py RUN_DIR [--min 20]
"""

from __future__ import annotations

import argparse
import gzip
import json
from pathlib import Path


def _records(replay: Path):
    """The replay's records; an episode still being written ends early (a truncated gzip)."""
    with gzip.open(replay, "rt") as f:
        try:
            for line in f:
                yield json.loads(line)
        except (EOFError, json.JSONDecodeError):
            return


def still_stretches(replay: Path, min_s: float) -> list[dict]:
    running: set[str] = set()
    since: dict[str, tuple[float, tuple]] = {}  # player -> (time it last moved or chatted, position then)
    longest: dict[str, tuple[float, float, tuple]] = {}
    for d in _records(replay):
        kind, t = d["type"], d.get("t", 0.0)
        if kind == "program":
            (running.add if d["what"] == "start" else running.discard)(d["player"])
            since.pop(d["player"], None)
        elif kind == "event" and d["event"].get("event") == "chat":
            since.pop(d["event"].get("player"), None)
        elif kind == "frame":
            for name, x, y, z, *_ in d["players"]:
                pos = (round(x, 2), round(y, 2), round(z, 2))
                if name not in running:
                    continue
                start, at = since.get(name, (t, pos))
                if at != pos:
                    start, at = t, pos
                since[name] = (start, at)
                if t - start > longest.get(name, (0.0, 0.0, ()))[0]:
                    longest[name] = (t - start, start, pos)
    return [
        {"player": p, "still_s": round(s, 1), "from_t": round(t0, 1), "at": pos}
        for p, (s, t0, pos) in sorted(longest.items())
        if s >= min_s
    ]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", type=Path)
    ap.add_argument("--min", type=float, default=20.0, help="seconds (default 20)")
    args = ap.parse_args()
    replays = sorted(args.run.glob("**/episode_*/replay.jsonl.gz"))
    if not replays:
        raise SystemExit(f"{args.run}: no episode replays (replay.jsonl.gz) below it")
    for replay in replays:
        for row in still_stretches(replay, args.min):
            print(json.dumps({"episode": str(replay.parent.relative_to(args.run)), **row}))


if __name__ == "__main__":
    main()
