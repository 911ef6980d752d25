"""What the people's tests read of a run: the page's address it prints, a player's replay frames."""

from __future__ import annotations

import gzip
import json
import subprocess
from pathlib import Path


def page_url(proc: subprocess.Popen) -> str:
    """The people's page's address, from the run's output (`people: open URL to play`)."""
    assert proc.stdout is not None
    for line in proc.stdout:
        if line.startswith("people: open "):
            return line.split()[2]
    raise AssertionError("no page address printed")


def frames(run_dir: Path, player: str, episode: int = 0) -> list[list]:
    """`player`'s entries in the replay's frames of an episode."""
    with gzip.open(run_dir / f"episode_{episode:03d}" / "replay.jsonl.gz", "rt") as f:
        found = [json.loads(line) for line in f]
    return [p for f in found if f["type"] == "frame" for p in f["players"] if p[0] == player]
