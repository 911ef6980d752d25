"""A sample whose team is an Inspect agent (`-T team=agent`): its series runs beside the agent.

`--solver` replaces a task's solver, so the series cannot be the solver's work: the task's setup step
(`seat_series`: Task(setup=...), which Inspect runs whatever the solver) opens a seat (teams/tools/seat.py)
at the sample's side, starts the sample's series in the background with the `agent` team seated there
(its entrant the agent's name, Inspect's version and the evaluation's model: `agent:react/0.3.285@MODEL`),
and puts the seat's key in the sample's store and metadata, where the tools find it (tools.py). The agent
(the task's solver, or the user's --solver) then plays through the tools while the series runs.

The series' end closes the seat (`Seat.finish`): every call then says the run is over. The agent's end,
however it came (it stopped, or a limit of Inspect's ended its loop), is the scorer's start (`finished`):
the seat is left (`Seat.leave`: its players idle, the world goes on), the series plays on to its end, and
the scorer scores it as any series; a time or working limit cuts the series instead, as it cuts any
team's (its finished episodes are scored). `cleanup` ends a series still running when a sample failed.
"""

from __future__ import annotations

import asyncio
import dataclasses
from pathlib import Path
from typing import Any

import inspect_ai
from inspect_ai.log._samples import sample_active
from inspect_ai.model import get_model
from inspect_ai.solver import Generate, Solver, TaskState, solver
from inspect_ai.util import concurrency, sample_limits, store

from pillagerbench.experiments.series import run_series
from pillagerbench.host.machine import choose_parallel
from pillagerbench.match.run import scenario_from_config
from pillagerbench.rundir import SeriesSpec
from pillagerbench.teams.tools import SEATS, Seat, open_seat

from . import transcript
from .experiment_dir import add_series
from .solver import MATCHES, epoch_spec
from .tools import SEAT, seat_tools

UNNAMED = "inspect-agent"  # the agent's name when Inspect names no solver

# the series playing now, by seat key (a task is no value for the sample's store)
RUNNING: dict[str, asyncio.Task[dict[str, Any]]] = {}


def identity(key: str) -> dict[str, Any]:
    """The agent team's options for this sample: its seat and who plays from it."""
    active = sample_active()
    return {
        "seat": key,
        "agent": (active.agent_name if active is not None else None) or UNNAMED,
        "agent_version": inspect_ai.__version__,
        "agent_model": str(get_model()),
    }


@solver
def seat_series(root: str, task: str) -> Solver:
    """The setup step: the sample's seat opened and its series started (played into
    `<root>/series/<series id>_epoch<k>`); the agent begins once the series has its place among the
    matches played at once."""

    async def solve(state: TaskState, generate: Generate) -> TaskState:
        side = state.metadata["side"]
        spec = epoch_spec(SeriesSpec.from_dict(state.metadata["series"]), state.epoch)
        seat = Seat(scenario_from_config(spec.config), side)
        key = open_seat(seat)
        spec = dataclasses.replace(spec, config=spec.config.updated({side: identity(key)}))
        spec, where = add_series(Path(root), spec, task)
        state.metadata.update(run_dir=str(where.resolve()), seat=key)
        store().set(SEAT, key)
        transcript.say(f"{spec.id}: the agent plays {side} from {key}; the series' directory: {where}")
        placed = asyncio.Event()
        running = RUNNING[key] = asyncio.create_task(_play(spec, where, Path(root), seat, placed))
        waiting = asyncio.create_task(placed.wait())
        await asyncio.wait([running, waiting], return_when=asyncio.FIRST_COMPLETED)
        waiting.cancel()
        if running.done() and running.exception() is not None:
            await finished(state)  # raises the series' failure: the sample's error
        state.tools = list(seat_tools(seat))  # for solvers that call the model with the task's tools (generate())
        return state

    return solve


async def _play(spec: SeriesSpec, where: Path, root: Path, seat: Seat, placed: asyncio.Event) -> dict[str, Any]:
    try:
        async with concurrency(MATCHES, choose_parallel().parallel):
            placed.set()
            return await run_series(spec, where, root, say=transcript.say)
    finally:
        seat.finish()


def _out_of_time() -> bool:
    """The sample's time or working limit was reached (the solver was cut, not finished)."""
    limits = sample_limits()
    return any(limit.limit is not None and limit.usage >= limit.limit for limit in (limits.time, limits.working))


async def finished(state: TaskState) -> None:
    """The agent has stopped: its series played to its end without it (cut when out of time), then its
    episodes in the transcript and its summary in the metadata; a failure of the series is raised."""
    key = str(state.metadata.get("seat"))
    running = RUNNING.get(key)
    if running is None:
        return
    seat = SEATS.get(key)
    if not running.done():
        if _out_of_time() or seat is None:
            running.cancel()
        else:
            seat.leave()
    await asyncio.wait([running])  # (a scorer cut meanwhile leaves it to `end_series`)
    RUNNING.pop(key, None)
    SEATS.pop(key, None)
    transcript.episodes(Path(state.metadata["run_dir"]))
    if not running.cancelled():
        state.metadata["summary"] = running.result()


async def end_series(state: TaskState) -> None:
    """The task's cleanup: a series still running after its sample failed or its scorer was cut is cut."""
    key = str(state.metadata.get("seat"))
    running = RUNNING.pop(key, None)
    if running is not None:
        running.cancel()
        await asyncio.wait([running])
        SEATS.pop(key, None)
