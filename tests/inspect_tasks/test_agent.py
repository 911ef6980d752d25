"""`-T team=agent`: an Inspect agent plays the team through the game's tools, on real episodes (lockstep
clock, 10-second episodes against do_nothing): the task's default react() agent until the run is over,
and a `--solver` of the user's (examples/inspect/my_agent.py) ended by Inspect's message limit, after
which its players idle to the series' end. Each run is scored, its transcript holds every tool call and
its result, and red's tools.jsonl lists the calls."""

from __future__ import annotations

import asyncio
import json
import re
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import inspect_ai
import pytest
from inspect_ai.log import EvalSample
from inspect_ai.model import ModelOutput, get_model
from inspect_ai.solver import SolverSpec
from inspect_ai.tool import ToolCall, ToolDef, ToolError

from pillagerbench.inspect_tasks.tools import NoSeat, current_seat, inspect_tool, seat_tools
from pillagerbench.rundir import RunDir
from pillagerbench.scenarios import make_scenario
from pillagerbench.teams.tools import Seat, briefing
from tests.inspect_tasks.conftest import ROOT

AGENT_ARGS = {"team": "agent", "clock": "lockstep", "episodes": 1, "episode_length": 10, "opponents": "do_nothing"}
MINE = {"player": "Ryn", "name": "red_mushroom_block", "count": 2}


def call(tool: str, **arguments: Any) -> ModelOutput:
    return ModelOutput.for_tool_call(model="mockllm/model", tool_name=tool, tool_arguments=arguments)


def turn(*calls: tuple[str, dict[str, Any]]) -> ModelOutput:
    """One model turn with several tool calls (run at once)."""
    out = call(calls[0][0], **calls[0][1])
    assert out.message.tool_calls is not None
    out.message.tool_calls += [ToolCall(id=f"call_{i}", function=f, arguments=a) for i, (f, a) in enumerate(calls[1:])]
    return out


def play(tmp_path: Path, outputs: Iterator[ModelOutput], **eval_args: Any) -> EvalSample:
    """`inspect eval pillagerbench/mushroom_war -T team=agent ...` in-process; its one sample."""
    [log] = inspect_ai.eval(
        "pillagerbench/mushroom_war",
        task_args={**AGENT_ARGS, "run_dir": str(tmp_path / "runs")},
        model=get_model("mockllm/model", custom_outputs=outputs),
        log_dir=str(tmp_path / "logs"),
        display="none",
        limit=1,
        **eval_args,
    )
    assert log.status == "success", log.error
    assert log.samples is not None
    return log.samples[0]


def tool_events(sample: EvalSample) -> list[Any]:
    return [e for e in sample.events if e.event == "tool"]


def red_calls(run_dir: Path) -> list[dict[str, Any]]:
    lines = (run_dir / "episode_000" / "red" / "tools.jsonl").read_text().splitlines()
    return [json.loads(line) for line in lines[1:]]  # (the first line: the clock)


def default_agent_outputs() -> Iterator[ModelOutput]:
    yield call("status")
    for _ in range(3):
        yield call("mineBlock", **MINE)
    yield call("mineBlock", player="Ryn", name="red_mushroom_block", point=[1, 2])  # the seat refuses it
    yield turn(("mineBlock", MINE), ("mineBlock", {**MINE, "player": "Raze"}))  # both players at once
    while True:
        yield call("wait", player="Raze", ticks=100)


def test_the_default_agent_plays_until_the_run_is_over(tmp_path: Path) -> None:
    sample = play(tmp_path, default_agent_outputs())
    assert isinstance(sample.input, str) and sample.input.startswith(briefing(make_scenario("mushroom_war"), "red"))
    events = tool_events(sample)
    assert [e.function for e in events[:7]] == ["status"] + ["mineBlock"] * 6
    assert json.loads(events[0].result)["phase"] == "pre_game"
    assert "Mined 2 red_mushroom_block" in events[1].result
    assert events[4].error.message == "mineBlock: bad arguments: point: [1, 2] is too short"
    assert events[-1].function == "wait" and "the run is over" in events[-1].error.message  # then it stopped
    run_dir = Path(sample.metadata["run_dir"])
    calls = red_calls(run_dir)
    logged, seen = [(c["tool"], c["arguments"]) for c in calls], [(e.function, e.arguments) for e in events]
    parallel = slice(5, 7)  # (one turn's two calls, in the order they ended)
    assert logged[:5] == seen[:5] and logged[7:] == seen[7 : len(calls)]
    assert sorted(logged[parallel], key=str) == sorted(seen[parallel], key=str)
    assert len(calls) >= 7 and calls[4]["refused"].endswith("is too short")
    assert calls[5]["tick_start"] == calls[6]["tick_start"]  # one turn's calls start on one tick
    [record] = RunDir(run_dir).records()
    assert record.status == "ok" and record.red_entrant.label == f"agent:react/{inspect_ai.__version__}@mockllm/model"
    assert sample.scores is not None
    assert sample.scores["series_score"].value["points"] == record.red_score


def my_agent_outputs() -> Iterator[ModelOutput]:
    while True:
        yield call("mineBlock", **MINE)


def test_a_solver_of_ones_own_plays_until_a_limit_and_the_series_finishes_without_it(tmp_path: Path) -> None:
    solver = SolverSpec(str(ROOT / "examples" / "inspect" / "my_agent.py"))
    sample = play(tmp_path, my_agent_outputs(), solver=solver, message_limit=6)
    assert sample.limit is not None and sample.limit.type == "message"
    events = tool_events(sample)
    assert events and all(e.function == "mineBlock" and not e.error for e in events)
    run_dir = Path(sample.metadata["run_dir"])
    assert [c["tool"] for c in red_calls(run_dir)] == ["mineBlock"] * len(events)
    [record] = RunDir(run_dir).records()  # the whole episode, played on without the agent
    assert record.status == "ok" and record.red_entrant.label.startswith("agent:my_agent/")
    assert record.problems["red"] == ["the agent left: its players did nothing for the rest of the episode"]
    assert sample.scores is not None and sample.scores["series_score"].value["points"] == record.red_score


def test_the_tools_are_the_seats_declared_tools_and_a_refusal_is_a_tool_error() -> None:
    seat = Seat(make_scenario("dash_and_dine"), "blue")
    tools = [ToolDef(t) for t in seat_tools(seat)]
    assert [t.name for t in tools] == [s.name for s in seat.tools]
    for tool, spec in zip(tools, seat.tools, strict=True):
        assert tool.description == spec.description and tool.parallel
        assert set(tool.parameters.properties) == set(spec.parameters["properties"])
        assert tool.parameters.required == spec.parameters["required"]
    observe = inspect_tool(seat, seat.specs["observe"])
    with pytest.raises(ToolError, match=re.escape("player 'Ryn' is not on the blue team")):
        asyncio.run(observe(player="Ryn"))
    with pytest.raises(NoSeat, match="-T team=agent"):
        current_seat()  # outside a sample of -T team=agent


def test_the_example_is_the_docs() -> None:
    doc = (ROOT / "docs" / "inspect.md").read_text()
    for name in ("my_agent.py", "openai_agents_team.py"):
        assert f"```python\n{(ROOT / 'examples' / 'inspect' / name).read_text()}```" in doc, name


def test_an_agent_framework_plays_through_inspects_agent_bridge(tmp_path: Path) -> None:
    pytest.importorskip("agents", reason="openai-agents is not installed (docs/inspect.md: not a dependency)")

    def outputs() -> Iterator[ModelOutput]:
        while True:
            yield call("mineBlock", **MINE)
            yield ModelOutput.from_content(model="mockllm/model", content="Mined; next turn.")

    solver = SolverSpec(str(ROOT / "examples" / "inspect" / "openai_agents_team.py"))
    sample = play(tmp_path, outputs(), solver=solver)
    run_dir = Path(sample.metadata["run_dir"])
    [record] = RunDir(run_dir).records()
    assert record.status == "ok" and record.red_entrant.label.startswith("agent:openai_agents_team/")
    assert "mineBlock" in [c["tool"] for c in red_calls(run_dir)]  # the SDK's calls reached the seat
