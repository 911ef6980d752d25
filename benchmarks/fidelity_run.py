"""How long a fidelity run (or any experiment run) took and under what load (issue 11's target:
8 opponents x 10 episodes in <= 45 min on a 2-core machine with no episode flagged for lag).

Reads a finished run directory: wall time from the experiment's creation to the last episode
written, episodes per hour, episodes flagged for lag, server TPS and the bots' late physics ticks.
Prints JSON.

    python benchmarks/fidelity_run.py RUN_DIR
"""

from __future__ import annotations

import json
import sys
from datetime import datetime
from pathlib import Path


def summary(run: Path) -> dict:
    """An experiment's run directory (experiment.json, series/*/) or a single match's (manifest.json)."""
    head = next((run / name for name in ("experiment.json", "manifest.json") if (run / name).is_file()), None)
    if head is None:
        sys.exit(f"{run}: not a run directory (no experiment.json or manifest.json)")
    created = datetime.strptime(json.loads(head.read_text())["created"], "%Y-%m-%dT%H:%M:%S%z")
    episodes, last = [], created.timestamp()
    for path in sorted([*run.glob("series/*/episode_*/episode.json"), *run.glob("episode_*/episode.json")]):
        episodes.append(json.loads(path.read_text()))
        last = max(last, path.stat().st_mtime)
    ok = [e for e in episodes if e.get("status") == "ok"]
    wall_s = last - created.timestamp()
    tps = [e["server_tps"] for e in ok if e.get("server_tps")]
    late = [lag.get("late_pct", 0) for e in ok for lag in (e.get("bot_lag") or {}).values() if lag]
    return {
        "run": str(run),
        "episodes": len(episodes),
        "ok": len(ok),
        "flagged_for_lag": sum(bool(e.get("lagged")) for e in episodes),
        "wall_min": round(wall_s / 60, 1),
        "episodes_per_hour": round(len(ok) / wall_s * 3600, 1) if wall_s > 0 else None,
        "server_tps": [min(tps), max(tps)] if tps else None,
        "bot_late_ticks_pct_max": max(late) if late else None,
        "longest_episode_s": max((e.get("duration_s") or 0 for e in episodes), default=None),
    }


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: python benchmarks/fidelity_run.py RUN_DIR [RUN_DIR ...]")
    for arg in sys.argv[1:]:
        print(json.dumps(summary(Path(arg))))
