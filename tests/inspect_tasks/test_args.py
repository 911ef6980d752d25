"""The task arguments made into series, without playing: the generalization design's keys, model
against model, each epoch on its own seeds and each LLM side naming its real model."""

from __future__ import annotations

import pytest

from pillagerbench.inspect_tasks.args import TaskArgs, TaskArgumentError, overrides, parse, series, side_of
from pillagerbench.inspect_tasks.solver import epoch_spec


def test_arguments_become_the_generalization_designs_keys() -> None:
    args = parse(
        "mushroom_war",
        ("mushroom_war",),
        {
            "opponents": "balanced,passive",
            "sides": ["red", "blue"],
            "split": "test",
            "episodes": 2,
            "episode_length": 30,
            "paper": True,
        },
    )
    argv = overrides(args, roles=[])
    assert "experiment.opponents=[balanced,passive]" in argv and "experiment.sides=[red,blue]" in argv
    assert {
        "experiment.arenas.test=2",
        "experiment.arenas.paper=0",
        "episode_length=30",
        "paper=true",
        "llm=inspect",
    } <= set(argv)
    specs = series("mushroom_war", args, roles=[])
    assert [(s.red, s.blue, side_of(s)) for s in specs] == [
        ("cot", "balanced", "red"),
        ("balanced", "cot", "blue"),
        ("cot", "passive", "red"),
        ("passive", "cot", "blue"),
    ]
    assert all(s.config.split == "test" and s.episodes == 2 for s in specs)


def test_model_roles_for_both_sides_make_the_team_play_itself() -> None:
    args = TaskArgs(scenarios=("dash_and_dine",), team="tacticrafter", sides=("blue",))
    [spec] = series("dash_and_dine", args, roles=["red", "blue", "grader"])
    assert (spec.red_team, spec.blue_team, side_of(spec)) == ("tacticrafter", "tacticrafter", "red")


def test_each_epoch_has_its_own_seeds_and_names_the_real_model(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("INSPECT_EVAL_MODEL", "mockllm/model")  # get_model() outside an evaluation
    [spec] = series("mushroom_war", TaskArgs(scenarios=("mushroom_war",), opponents=("passive",)), roles=[])
    first, second = epoch_spec(spec, 1), epoch_spec(spec, 2)
    assert first.seed == spec.seed != second.seed == second.config.seed
    assert (first.id, second.id) == (f"{spec.id}_epoch1", f"{spec.id}_epoch2")
    assert first.config.red.llm.model == "mockllm/model" and not first.config.blue.llm.given()


def test_a_layout_replaces_the_split() -> None:
    args = parse("mushroom_war", ("mushroom_war",), {"opponents": "passive", "layout": 7})
    [spec] = series("mushroom_war", args, roles=[])
    assert spec.id.endswith("_cot_vs_passive_layout-7") and (spec.config.layout, spec.config.split) == (7, None)
    with pytest.raises(TaskArgumentError, match="layout=7 and split=test: give one or the other"):
        parse("mushroom_war", ("mushroom_war",), {"layout": 7, "split": "test"})
    with pytest.raises(TaskArgumentError, match="layout=nowhere.json: no such layout file"):
        series("mushroom_war", TaskArgs(scenarios=("mushroom_war",), opponents=("passive",), layout="nowhere.json"), [])


def test_the_clock_argument_picks_the_runs_clock_and_a_bad_one_names_the_clocks() -> None:
    args = parse("mushroom_war", ("mushroom_war",), {"opponents": "passive", "clock": "lockstep"})
    assert "clock=lockstep" in overrides(args, roles=[])
    [spec] = series("mushroom_war", args, roles=[])
    assert spec.config.clock.mode == "lockstep"
    [default] = series("mushroom_war", TaskArgs(scenarios=("mushroom_war",), opponents=("passive",)), roles=[])
    assert default.config.clock.mode == "real"
    with pytest.raises(TaskArgumentError, match="clock 'fast'.*lockstep, real"):
        series("mushroom_war", parse("mushroom_war", ("mushroom_war",), {"clock": "fast"}), roles=[])


def test_the_agent_team_plays_each_side_asked_from_a_seat_opened_per_sample() -> None:
    args = parse("mushroom_war", ("mushroom_war",), {"team": "agent", "sides": "red,blue", "opponents": "passive"})
    specs = series("mushroom_war", args, roles=[])
    assert [(s.red, s.blue, side_of(s)) for s in specs] == [("agent", "passive", "red"), ("passive", "agent", "blue")]
    assert all(s.config.side(side_of(s)).model_dump().get("seat") is None for s in specs)  # opened by the setup step
