"""The scorings an episode can be played under (config `scoring`, docs/faithful.md). Each owns its
sampling: when it reads the game master's score, what it keeps, and where it writes it.

- clean (the default): the game master's score each second from the clock's start and at exactly the
  whistle; timeline.json.
- upstream: also upstream's samples: play (and every player's code) goes on past the whistle until
  upstream's "L s" sample, the (L+1)-th line of a per-second rewards file whose lines start
  UPSTREAM_WAIT_S + 1 s after the clock; the game master's `upstream_scores` applies the scenario's
  quirks. Such an episode records both scores, its headline being upstream's; timeline_upstream.json.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

from pillagerbench.config.registry import Registry
from pillagerbench.rundir import EpisodeDir
from pillagerbench.scenarios.upstream import UPSTREAM_WAIT_S
from pillagerbench.server.clock import GameClock


class CleanScoring:
    """The score each second, and the final one at the whistle: `second(t, scores)` is called with each."""

    name = "clean"

    def __init__(self) -> None:
        self.timeline: list[dict[str, Any]] = []

    async def sample(
        self, gm, clock: GameClock, start: float, length: float, second: Callable[[int, dict], None]
    ) -> None:
        try:
            for t in range(int(length)):
                async with clock.at(start + t, "scores"):  # lockstep: read at that tick exactly
                    scores = await gm.scores()
                self.timeline.append({"t": t, **scores})
                second(t, scores)
        finally:
            await clock.let_go("scores")

    def final(self, length: float, scores: dict[str, float]) -> None:
        self.timeline.append({"t": length, **scores})

    def write(self, out: Path) -> None:
        EpisodeDir(out).timeline_path(self.name).write_text(json.dumps(self.timeline))


class UpstreamScoring:
    """Upstream's samples (lines 0 … L of its rewards file, each at UPSTREAM_WAIT_S + line + 1 s)."""

    name = "upstream"

    def __init__(self) -> None:
        self.timeline: list[dict[str, Any]] = []

    async def sample(self, gm, clock: GameClock, start: float, length: float, runs: dict[str, int]) -> None:
        try:
            for line in range(int(length) + 1):
                t = UPSTREAM_WAIT_S + line + 1
                async with clock.at(start + t, "upstream-scores"):
                    scores = await gm.upstream_scores(dict(runs))
                self.timeline.append({"t": t, "line": line, **scores})
        finally:
            await clock.let_go("upstream-scores")

    def write(self, out: Path) -> None:
        EpisodeDir(out).timeline_path(self.name).write_text(json.dumps(self.timeline))


# config `scoring`: every episode records the clean score as well
SCORINGS: Registry[type[CleanScoring] | type[UpstreamScoring]] = Registry(
    "scoring", {s.name: s for s in (CleanScoring, UpstreamScoring)}
)
