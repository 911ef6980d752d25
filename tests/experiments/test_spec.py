"""Experiment configs build the paper's experiment designs as series."""

from __future__ import annotations

import pytest

from pillagerbench.config.compose import ConfigError, load_config
from pillagerbench.config.schema import RunConfig
from pillagerbench.experiments import build_series, builtin_teams


def build(*argv):
    return build_series(RunConfig.of(load_config(list(argv))), list(argv))


def test_builtin_teams_in_the_papers_order():
    assert builtin_teams("mushroom_war") == ["do_nothing", "aggressive", "balanced", "passive", "slimy"]
    assert builtin_teams("dash_and_dine") == [
        "do_nothing",
        "berries",
        "cake_beetroot",
        "melon_pumpkin",
        "potato_cookie",
    ]


def test_round_robin_is_every_pairing_with_20_episodes():
    series = build("experiment=round_robin_dash_and_dine")
    assert len(series) == 25 and {s.episodes for s in series} == {20}
    assert {(s.red, s.blue) for s in series} == {
        (r, b) for r in builtin_teams("dash_and_dine") for b in builtin_teams("dash_and_dine")
    }
    assert all(s.config.scenario.name == "dash_and_dine" for s in series)
    assert len({s.id for s in series}) == 25 and len({s.seed for s in series}) == 25


def test_main_benchmark_is_150_episodes_in_series_of_5():
    series = build("experiment=main_benchmark", "experiment.team=do_nothing", "episode_length=60")
    assert len(series) == 30 and sum(s.episodes for s in series) == 150
    assert {s.repetition for s in series} == {0, 1, 2}
    assert all(s.config.red.name == "do_nothing" and s.config.episode_length == 60 for s in series)
    assert series[0].keeps_checkpoint(4) and not series[0].keeps_checkpoint(3)


def test_variants_set_team_options_and_models():
    series = build("experiment=ablation_models", "experiment.team=do_nothing", "experiment.repetitions=1")
    models = {s.red: s.config.llm.model for s in series}
    assert models == {
        "gpt-4o": "gpt-4o-2024-08-06",
        "gemini-2.0-flash": "google/gemini-2.0-flash-001",
        "o3-mini": "openai/o3-mini",
    }
    assert {s.config.llm.provider for s in series if s.red == "o3-mini"} == {"openrouter"}
    series = build("experiment=ablation_modules", "experiment.team=do_nothing", "experiment.repetitions=1")
    opts = {s.red: s.config.red.options.get("enable_causal") for s in series}
    assert opts == {"tacticrafter": None, "tacticrafter_no_causal": False, "tacticrafter_no_opponent": None}


def test_self_play_checkpoints_feed_evaluation_series():
    series = build(
        "experiment=self_play",
        "experiment.team=do_nothing",
        "experiment.repetitions=1",
        "experiment.scenarios=[mushroom_war]",
    )
    play = series[0]
    assert (play.red_team, play.blue_team, play.episodes) == ("do_nothing", "do_nothing", 20)
    assert play.checkpoint_at == [4, 9, 14, 19]
    evals = series[1:]
    assert len(evals) == 5 * 5 and {s.episodes for s in evals} == {1}
    assert {s.group_x for s in evals} == {0, 5, 10, 15, 20}
    assert all(s.after == ([play.id] if s.group_x else []) for s in evals)


def test_adaptation_trains_then_meets_same_and_different_opponents():
    series = build(
        "experiment=adaptation",
        "experiment.team=do_nothing",
        "experiment.repetitions=1",
        "experiment.scenarios=[dash_and_dine]",
    )
    train = [s for s in series if s.group == "training"]
    evals = [s for s in series if s.group in ("same", "different")]
    assert len(train) == 5 and {s.episodes for s in train} == {5} and all(s.checkpoint_at == [4] for s in train)
    assert len(evals) == 25 and sum(s.group == "same" for s in evals) == 5
    assert all(s.episode_offset == 5 and s.checkpoint["red"]["episode"] == 4 for s in evals)


def test_choosing_teams_outside_the_experiment_is_refused():
    with pytest.raises(ConfigError, match="experiment.team"):
        build("experiment=main_benchmark", "red=cot")


def test_symmetry_plays_each_pairing_in_both_orders_and_mirrors_once():
    series = build("experiment=symmetry")
    got = [(s.scenario, s.red, s.blue, s.episodes) for s in series]
    assert got[:2] == [("mushroom_war", "balanced", "passive", 6), ("mushroom_war", "passive", "balanced", 6)]
    assert ("dash_and_dine", "potato_cookie", "berries", 6) in got
    assert [g for g in got if g[1] == g[2]] == [("mushroom_war", "passive", "passive", 6)]
    assert len(got) == 9


def test_symmetry_pairing_without_a_team_names_what_is_missing():
    with pytest.raises(ConfigError) as err:
        build("experiment=symmetry", "experiment.pairings=[{scenario: mushroom_war, a: passive}]")
    assert str(err.value) == "experiment.pairings.0.b: missing (a pairing takes scenario, a, b)"


def test_an_unknown_key_of_a_variant_is_one_line_naming_the_keys_it_takes():
    with pytest.raises(ConfigError) as err:
        build("experiment=main_benchmark", "experiment.variants={fast: {team: cot, team_option: {attempts: 1}}}")
    assert str(err.value) == (
        "experiment.variants.fast.team_option: unknown key (a variant takes team, team_options, llm, llm_options)"
    )


def test_a_variant_plays_its_own_keys_over_the_experiments():
    series = build(
        "experiment=main_benchmark",
        "experiment.team=cot",
        "experiment.llm_options.model=base-model",
        "experiment.team_options.attempts=2",
        "experiment.variants={same: null, other: {team: do_nothing, team_options: {}}, own: {llm_options: {model: m2}}}",
        "experiment.repetitions=1",
        "experiment.scenarios=[mushroom_war]",
    )
    played = {s.red: (s.red_team, s.config.red.options, s.config.llm.model) for s in series}
    assert played == {
        "same": ("cot", {**played["same"][1], "attempts": 2}, "base-model"),
        "other": ("do_nothing", {}, "base-model"),
        "own": ("cot", played["same"][1], "m2"),
    }


def test_fidelity_plays_every_builtin_opponent_against_do_nothing_as_blue():
    series = build("experiment=fidelity")
    got = {(s.scenario, s.red, s.blue) for s in series}
    assert got == {
        (sc, "do_nothing", team) for sc in ("mushroom_war", "dash_and_dine") for team in builtin_teams(sc)[1:]
    }
    assert {s.episodes for s in series} == {10}


def test_fidelity_on_both_sides_and_a_bad_side():
    series = build("experiment=fidelity", "experiment.sides=[blue,red]", "experiment.scenarios=[mushroom_war]")
    assert len(series) == 8 and ("mushroom_war", "slimy", "do_nothing") in {(s.scenario, s.red, s.blue) for s in series}
    with pytest.raises(ConfigError, match="experiment.sides.0='green': input should be 'blue' or 'red'"):
        build("experiment=fidelity", "experiment.sides=[green]")
