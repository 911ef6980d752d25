"""The suite's own reference figures (`reference_figures.json` beside this module): each built-in
opponent's points against do_nothing, mean and 95 % interval over n episodes, per scoring, as measured
under the suite version they name (docs/suite-versions.md). Read by the fidelity table
(metrics/reference.py) and by the plan, which takes from them how much one episode's points spread."""

from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path

from pillagerbench.stats.sample_size import sd_of

FIGURES = Path(__file__).resolve().parent / "reference_figures.json"


@lru_cache(maxsize=1)
def reference_figures() -> dict:
    """{"suite", "status", "source", "scenarios": {scenario: {team: {scoring: {"mean", "ci", "n"}}}}}
    (Dash & Dine ×0.1, as reported)."""
    return json.loads(FIGURES.read_text())


def widest_spread(scenario: str, scoring: str = "clean") -> float | None:
    """The largest standard deviation of one episode's points among the scenario's built-in opponents
    (the spread behind each reported interval), or None for a scenario without figures."""
    teams = reference_figures()["scenarios"].get(scenario, {})
    spreads = [sd_of(v[scoring]["ci"], v[scoring]["n"]) for v in teams.values() if scoring in v]
    return max(spreads) if spreads else None
