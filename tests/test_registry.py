"""One registry type for every kind of named thing a configuration chooses (issue 40, item 3): each
kind is a `Registry`, and a name that is not there fails in one form, naming every known one."""

from __future__ import annotations

import pytest

from pillagerbench.config.compose import ConfigError
from pillagerbench.config.registry import Registry
from pillagerbench.experiments.spec import DESIGNS
from pillagerbench.llm.presets import presets
from pillagerbench.match.parts import PARTS
from pillagerbench.match.scoring import SCORINGS
from pillagerbench.scenarios import SCENARIOS
from pillagerbench.scenarios.layout import SPLITS
from pillagerbench.teams import TEAMS, find_team

KINDS = {
    "team": TEAMS,
    "scenario": SCENARIOS,
    "scoring": SCORINGS,
    "design": DESIGNS,
    "match part": PARTS,
    "split": SPLITS,
    "llm preset": presets(),
}


@pytest.mark.parametrize("kind", KINDS)
def test_every_kind_fails_in_one_form(kind):
    registry = KINDS[kind]
    assert isinstance(registry, Registry) and registry.kind == kind and len(registry) >= 2
    with pytest.raises(ConfigError) as caught:
        registry.find("cott")
    message = str(caught.value)
    assert message.startswith(f"unknown {kind} 'cott'; known: {', '.join(sorted(registry))}")
    assert registry.find(registry.names()[0]) is registry[registry.names()[0]]


def test_the_kinds_hold_what_the_configuration_chooses():
    assert {"mushroom_war", "dash_and_dine"} <= set(SCENARIOS)
    assert {"do_nothing", "balanced", "cot", "tacticrafter", "random"} <= set(TEAMS)
    assert list(SCORINGS) == ["clean", "upstream"]
    assert {"round_robin", "benchmark", "fidelity", "generalization"} <= set(DESIGNS)
    assert list(SPLITS) == ["paper", "dev", "test"]
    assert {"openai", "fake"} <= set(presets()) and "base" not in presets()


def test_a_team_name_that_is_nowhere_says_what_else_a_name_may_be():
    with pytest.raises(ConfigError, match=r"^unknown team 'cott'; known: agent, aggressive, .* \(or an import path"):
        find_team("cott")


def test_register_adds_once_and_refuses_a_second_item_under_one_name():
    things: Registry[object] = Registry("thing")

    @things.register("a")
    class A:
        pass

    assert things.register("b", 2) == 2 and things.names() == ["a", "b"] and things.find("a") is A
    things.register("a", A)  # the same item again: nothing changes
    with pytest.raises(ValueError, match="two things are registered under the name 'a'"):
        things.register("a", object())
    with pytest.raises(ConfigError, match=r"^unknown thing 1; known: a, b$"):
        things.find(1)
