"""live.json: the episode a series is playing (its clock and each side's points), written by the series
(experiments/series.py, through `LiveWriter`: at most twice a wall second) and read by an experiment's
display (experiments/progress.py)."""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping
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


class LiveWriter:
    """Writes a series' statuses to live.json through `write`: each episode's first and last, and between
    them at most one per `every_s` of wall time. It is for a display, and on the lockstep clock a game
    second can pass in a few milliseconds: a write each (about 3 ms) cost more than the game, for the
    world waits while the score sample that reports it is held."""

    def __init__(self, write: Callable[[Live], None], every_s: float = 0.5, now: Callable[[], float] = time.monotonic):
        self.write, self.every_s, self.now = write, every_s, now
        self.at, self.episode = float("-inf"), -1

    def __call__(self, status: Mapping[str, Any]) -> None:
        live, now = Live.of(status), self.now()
        if now - self.at >= self.every_s or live.episode != self.episode or live.t >= live.length:
            self.write(live)
            self.at, self.episode = now, live.episode
