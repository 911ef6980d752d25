"""What a series adds to its sample's transcript (`inspect view`), beside the model calls Inspect
records itself: one event per episode with its result, faults and refusals, each side's programs and
errors as the team wrote them (its artefact, e.g. cot.json), the score timeline, and the episode's
replay page (written here, `replay.html` in the episode directory, as `pillagerbench replay` does).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from inspect_ai.log import transcript

from pillagerbench.config.sides import SIDES
from pillagerbench.replay.page import write_replay
from pillagerbench.rundir import EpisodeDir, EpisodeRecord, RunDir, spoiled

REFUSED_SHOWN = 20  # refused actions listed per episode (the record counts them all)
CODE_KEYS = ("programs", "errors", "iterations", "agents", "problems")  # what an artefact says of the code run


def say(line: str) -> None:
    """The series runner's lines (resume, discarded episodes) as transcript events."""
    transcript().info(line, source="pillagerbench")


def episodes(where: Path) -> None:
    """One transcript event per episode played in the series directory `where`."""
    rundir = RunDir(where)
    for record in rundir.records():
        transcript().info(episode_event(record, rundir.files(record.episode)), source=f"episode {record.episode}")


def episode_event(record: EpisodeRecord, files: EpisodeDir) -> dict[str, Any]:
    event: dict[str, Any] = {
        "episode": record.episode,
        "status": record.status,
        "spoiled": spoiled(record),
        "error": record.error,
        "red": record.red,
        "blue": record.blue,
        "red_score": record.red_score,
        "blue_score": record.blue_score,
        "winner": record.winner,
        "layout": record.layout,
        "problems": record.problems,
        "refusals": record.refusals,
        "refused": _refused(files),
        "runs": record.runs,
        "lagged": record.lagged,
        "code": {side: team_code(files.side(side)) for side in SIDES},
        "timeline": _timeline(files),
        "replay": _replay(files),
        "episode_dir": str(files.path.resolve()),
    }
    return event


def team_code(out_dir: Path) -> dict[str, Any]:
    """The programs, errors and iterations of a side's artefacts (each JSON file the team wrote)."""
    found: dict[str, Any] = {}
    for path in sorted(out_dir.glob("*.json")) if out_dir.is_dir() else []:
        try:
            data = json.loads(path.read_text())
        except (OSError, ValueError):
            continue
        if isinstance(data, dict):
            found[path.name] = {k: data[k] for k in CODE_KEYS if k in data}
    return found


def _refused(files: EpisodeDir, most: int = REFUSED_SHOWN) -> list[dict[str, Any]]:
    """The first actions the server refused (world_events.jsonl's `refused` events: who, what, why)."""
    found: list[dict[str, Any]] = []
    try:
        with open(files.world_events_path) as f:
            for line in f:
                event = json.loads(line)
                if event.get("event") == "refused" and len(found) < most:
                    found.append(event)
    except (OSError, ValueError):
        pass
    return found


def _timeline(files: EpisodeDir) -> list[dict[str, float]]:
    try:
        return [{"t": p["t"], "red": p["red"], "blue": p["blue"]} for p in files.timeline()]
    except (OSError, ValueError):
        return []


def _replay(files: EpisodeDir) -> str | None:
    """The episode's replay page as a file URL (None when the episode left no recording)."""
    if not files.replay_path.exists():
        return None
    try:
        page, _ = write_replay(files.path)
    except (OSError, ValueError):
        return None
    return page.resolve().as_uri()
