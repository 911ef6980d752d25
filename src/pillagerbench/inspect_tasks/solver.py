"""The solver: one sample's series played by our series runner (experiments/series.py), exactly as
`pillagerbench run experiment=generalization` plays it, into its own run directory; the LLM teams ask
Inspect's models (llm=inspect), so every call is in the sample's transcript. At most as many matches
at once as our runner would choose for this machine (host/machine.py), whatever --max-samples says.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

from inspect_ai.model import get_model
from inspect_ai.solver import Generate, Solver, TaskState, solver
from inspect_ai.util import concurrency

from pillagerbench.config.sides import SIDES
from pillagerbench.experiments.series import run_series
from pillagerbench.host.machine import choose_parallel
from pillagerbench.rundir import SeriesSpec
from pillagerbench.teams import find_team

from . import transcript
from .experiment_dir import add_series

EPOCH_SEED = 100_003  # a later epoch plays the same series on other seeds (a replicate, not a copy)
MATCHES = "pillagerbench-matches"  # Inspect's concurrency name for the matches played at once


def epoch_spec(spec: SeriesSpec, epoch: int) -> SeriesSpec:
    """The series of one epoch: its own seed (epoch 1 keeps the series' own), and each LLM side's
    model named as Inspect gives it (the side's model role, else the evaluation's model), so the run
    directory, the entrants and the ledger's prices name the real model, not `eval`."""
    seed = spec.seed + EPOCH_SEED * (epoch - 1)
    changes: dict = {"seed": seed}
    for side in SIDES:
        team = spec.red_team if side == "red" else spec.blue_team
        if getattr(find_team(team), "uses_llm", False):
            changes[side] = {"llm": {"model": str(get_model(role=side))}}
    config = spec.config.updated(changes)
    return dataclasses.replace(spec, id=f"{spec.id}_epoch{epoch}", seed=seed, config=config)


@solver
def play_series(root: str, task: str) -> Solver:
    """Play the sample's series (metadata `series`) into `<root>/series/<series id>_epoch<k>`."""

    async def solve(state: TaskState, generate: Generate) -> TaskState:
        spec = epoch_spec(SeriesSpec.from_dict(state.metadata["series"]), state.epoch)
        spec, where = add_series(Path(root), spec, task)
        state.metadata["run_dir"] = str(where.resolve())  # a series cut by --time-limit scores what it finished
        async with concurrency(MATCHES, choose_parallel().parallel):
            summary: dict[str, Any] = await run_series(spec, where, Path(root), say=transcript.say)
        state.metadata["summary"] = summary
        transcript.episodes(where)
        state.completed = True
        return state

    return solve
