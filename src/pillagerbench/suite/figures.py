"""The suite's own reference figures (`reference_figures.json` beside this module): each built-in
opponent's points against do_nothing, mean and 95 % interval over n episodes, per scoring, as measured
under the suite version they name (docs/suite-versions.md). Read by the fidelity table
(metrics/reference.py) and by the plan, which takes from them how much one episode's points spread."""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from pydantic import BaseModel

from pillagerbench.stats.sample_size import sd_of

FIGURES = Path(__file__).resolve().parent / "reference_figures.json"


class Figure(BaseModel):
    """One opponent's points under one scoring: mean, 95 % interval (half-width), episodes."""

    mean: float
    ci: float
    n: int


class ReferenceFigures(BaseModel):
    about: str = ""
    suite: str  # the suite version they were measured under ("suite 1.1")
    status: str
    source: str
    scenarios: dict[str, dict[str, dict[str, Figure]]]  # scenario -> team -> scoring -> its figure

    def of(self, scenario: str, team: str, scoring: str) -> Figure | None:
        return self.scenarios.get(scenario, {}).get(team, {}).get(scoring)


@lru_cache(maxsize=1)
def reference_figures() -> ReferenceFigures:
    """The figures (Dash & Dine ×0.1, as reported)."""
    return ReferenceFigures.model_validate_json(FIGURES.read_text())


def widest_spread(scenario: str, scoring: str = "clean") -> float | None:
    """The largest standard deviation of one episode's points among the scenario's built-in opponents
    (the spread behind each reported interval), or None for a scenario without figures."""
    teams = reference_figures().scenarios.get(scenario, {})
    spreads = [sd_of(v[scoring].ci, v[scoring].n) for v in teams.values() if scoring in v]
    return max(spreads) if spreads else None
