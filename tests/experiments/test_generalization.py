"""experiment=generalization's series (issue 29, no server): the team against every built-in
opponent of each scenario, as red and as blue, on the paper's layout and on fresh test layouts; a
layout of the user's own and a bad `arenas` refused in one line; plan=true prices it."""

from __future__ import annotations

import pytest

from pillagerbench.config.compose import ConfigError, load_config
from pillagerbench.config.schema import RunConfig
from pillagerbench.experiments import build_series, builtin_teams
from pillagerbench.experiments.plan import build_plan

SMALL = ("experiment=generalization", "experiment.team=random", "experiment.arenas.paper=1", "experiment.arenas.test=2")


def build(*argv):
    return build_series(RunConfig.of(load_config(list(argv))), list(argv))


def test_every_opponent_both_sides_on_the_papers_and_on_test_layouts():
    series = build(*SMALL)
    seen = set()
    for s in series:
        side = "red" if s.red == "random" else "blue"
        opponent = s.blue if side == "red" else s.red
        arena = s.config.split
        seen.add((s.scenario, opponent, side, arena))
        assert s.config.layout == "paper" and s.episodes == {"paper": 1, "test": 2}[arena]
        assert s.id.endswith(f"_{arena}") and s.variant == "random" and s.config.side(side).name == "random"
    expected = {
        (sc, opponent, side, arena)
        for sc in ("mushroom_war", "dash_and_dine")
        for opponent in builtin_teams(sc)
        for side in ("red", "blue")
        for arena in ("paper", "test")
    }
    assert seen == expected and len(series) == len(expected) == 40
    assert sum(s.episodes for s in series) == 20 * 1 + 20 * 2
    assert build(*SMALL) == series  # the same command builds the same series: a resume is accepted


@pytest.mark.parametrize(
    "extra, expected",
    [
        (("split=test",), "'split=test': experiment 'generalization' chooses each series' layout itself"),
        (("layout=7",), "'layout=7': experiment 'generalization' chooses each series' layout itself"),
        (("experiment.arenas.test=-1",), "a split (paper, dev, test) -> episodes (an integer ≥ 0)"),
        (("experiment.arenas.paper=0", "experiment.arenas.test=0"), "at least one above 0"),
        (("experiment.sides=[left]",), "experiment.sides.0='left': input should be 'blue' or 'red'"),
        (
            ("experiment.arenas.hidden=2",),
            "experiment.arenas.hidden: no such key (experiment.arenas takes paper, test, dev)",
        ),
        (
            ("experiment.arenas={paper: 1, hidden: 2}",),
            "experiment.arenas: the value names a key it does not take (experiment.arenas takes paper, test, dev)",
        ),
    ],
    ids=[
        "split",
        "layout",
        "negative_episodes",
        "no_episodes",
        "bad_side",
        "unknown_split",
        "unknown_split_in_a_table",
    ],
)
def test_bad_input_is_one_line(extra, expected):
    with pytest.raises(ConfigError) as exc:
        build(*SMALL, *extra)
    assert expected in str(exc.value) and "\n" not in str(exc.value)


def test_dev_layouts_are_asked_for_by_their_key():
    series = build(*SMALL, "experiment.arenas.dev=1")
    dev = [s for s in series if s.config.split == "dev"]
    assert len(dev) == 20 and all(s.episodes == 1 and s.id.endswith("_dev") for s in dev)


def test_plan_prices_the_default_experiment():
    argv = ["experiment=generalization", "experiment.team=do_nothing", "parallel=4"]
    plan = build_plan(RunConfig.of(load_config(argv)), argv)
    assert (len(plan.series), plan.episodes) == (40, 120)
    assert 60 * 60 < plan.wall_low == plan.wall_high < 70 * 60  # 40 series of 3 × 120 s, 4 at once
