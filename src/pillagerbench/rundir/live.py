"""live.json: the episode a series is playing (its clock and each side's points), written each second
by the series (experiments/series.py) and read by an experiment's display (experiments/progress.py)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, fields
from typing import Any


@dataclass(frozen=True)
class Live:
    episode: int = 0
    t: float = 0.0  # seconds of game played
    length: float = 0.0  # the episode's length in seconds
    red: float = 0.0  # each side's points so far
    blue: float = 0.0
    ts: float = 0.0  # when it was written (time.time())

    @classmethod
    def of(cls, data: Mapping[str, Any]) -> Live:
        """A tick's status (match/parts.py `Progress`: episode, t, length, each side's points) or live.json's
        content; a key it lacks reads as 0."""
        return cls(**{f.name: data[f.name] for f in fields(cls) if f.name in data})
