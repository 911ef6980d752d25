"""The scorer: win, points, sabotage and dominance of the sample's series, from its run directory by
our metrics (metrics/runs.py reads the episodes as the report does, metrics/calibration.py gives
σ_blue as the report's, metrics/formulas.py `pairing` computes P, S, D, W), from the side of the
task's team. For a series with the team on red these are the report's numbers for that pairing
(`pillagerbench report RUN_DIR`). An episode spoiled on our side (rundir/faults.py: a failure of ours,
lag, the provider answering none of a team's calls) is in no score, as in the report; a series with
no usable episode is an error of the sample (Inspect retries it with --retry-on-error), not a loss.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, cast

from inspect_ai.scorer import (
    Metric,
    SampleScore,
    Score,
    Scorer,
    Target,
    Value,
    bootstrap_stderr,
    mean,
    metric,
    scorer,
    stderr,
)
from inspect_ai.solver import TaskState

from pillagerbench.metrics.calibration import resolve
from pillagerbench.metrics.columns import Col
from pillagerbench.metrics.formulas import pairing
from pillagerbench.metrics.runs import read_runs

from .seated import finished

NAMES = {"W": "win", "P": "points", "S": "sabotage", "D": "dominance"}


class NoResult(RuntimeError):
    """A series whose every episode was spoiled on our side: no result for either team."""


def series_scores(run_dir: Path, side: str) -> tuple[dict[str, float], int]:
    """P, S, D, W (named as NAMES) of the series from `side`'s point of view, and the episodes used."""
    runs = read_runs([run_dir])
    df = runs.episodes
    if not len(df):
        raise NoResult(f"{run_dir}: no usable episode (every one spoiled on our side: {len(runs.spoiled)})")
    sigma, _ = resolve(runs, fallback=True)
    scenario = str(df[Col.SCENARIO].iloc[0])
    ours, theirs = (Col.RED_SCORE, Col.BLUE_SCORE) if side == "red" else (Col.BLUE_SCORE, Col.RED_SCORE)
    opponent = str(df[Col.BLUE if side == "red" else Col.RED].iloc[0])
    s = sigma.get((scenario, opponent))
    estimates = pairing(df[ours], df[theirs], s.mean if s else None, s)
    return {NAMES[k]: float(e.mean) for k, e in estimates.items()}, len(df)


def known(inner: Metric, scores: list[SampleScore]) -> Value:
    """`inner` over the samples whose value is known: sabotage has none against do_nothing (σ_blue
    unknown; the report's "–"), and the report's mean over opponents leaves those out too."""
    compute: Any = inner  # Inspect's Metric type also admits the older form over a list of Score
    return cast(Value, compute([s for s in scores if not math.isnan(s.score.as_float())]))


@metric
def known_mean() -> Metric:
    """The mean of the known values (the report's "all opponents" sabotage leaves the unknown out)."""

    def compute(scores: list[SampleScore]) -> Value:
        return known(mean(), scores)

    return compute


@metric
def known_stderr() -> Metric:
    """The standard error of the known values."""

    def compute(scores: list[SampleScore]) -> Value:
        return known(stderr(), scores)

    return compute


METRICS = {name: [mean(), stderr(), bootstrap_stderr()] for name in NAMES.values()}
METRICS["sabotage"] = [known_mean(), known_stderr()]


@scorer(metrics=METRICS)
def series_score() -> Scorer:
    async def score(state: TaskState, target: Target) -> Score:
        await finished(state)  # an agent's series (-T team=agent) played to its end without the agent
        side = state.metadata["side"]
        values, used = series_scores(Path(state.metadata["run_dir"]), side)
        summary = state.metadata.get("summary", {})
        return Score(
            value=values,
            answer=f"{side}: " + ", ".join(f"{k} {v:g}" for k, v in values.items()),
            explanation=f"{used} episode(s) used, {summary.get('spoiled', 0)} spoiled on our side (in no score)",
            metadata={"side": side, "episodes_used": used, "run_dir": state.metadata["run_dir"]},
        )

    return score
