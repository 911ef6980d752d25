"""Where things are in a series directory (see series.py for the whole layout)."""

from __future__ import annotations

from pathlib import Path

EPISODES = "episodes.jsonl"
LEDGER = "llm_calls.jsonl"


def episode_dir(series_dir: Path, episode: int) -> Path:
    return Path(series_dir) / f"episode_{episode:03d}"


def state_dir(series_dir: Path, episode: int) -> Path:
    return Path(series_dir) / "state" / f"episode_{episode:03d}"


def checkpoint_dir(series_dir: Path, episode: int, side: str) -> Path:
    return Path(series_dir) / "checkpoints" / f"episode_{episode:03d}" / side


def episode_index(name: str) -> int | None:
    """The N of a directory named `episode_N` (None for any other name)."""
    try:
        return int(name.split("_", 1)[1])
    except (IndexError, ValueError):
        return None
