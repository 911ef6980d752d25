"""The declared tool surface: built from the primitives' documentation, one JSON schema per tool that
every front reads, a primitive's call played as the line of agent code it stands for; the entrant of an
outside agent is its declared name, version and model."""

from __future__ import annotations

import jsonschema
import pytest

from pillagerbench.config.compose import load_config
from pillagerbench.config.schema import RunConfig
from pillagerbench.players import primitives as prim
from pillagerbench.scenarios import SCENARIOS, make_scenario
from pillagerbench.teams.entrant import entrant_of
from pillagerbench.teams.tools.surface import PARAMETERS, call_code, primitives_of, tools_of


@pytest.mark.parametrize("key", list(SCENARIOS))
def test_every_tool_has_a_valid_schema_and_every_documented_primitive_is_a_tool(key):
    scenario = make_scenario(key)
    tools = {t.name: t for t in tools_of(scenario, "red")}
    for spec in tools.values():
        jsonschema.Draft202012Validator.check_schema(spec.parameters)
        assert spec.description
    documented = {p.name for p in primitives_of(list(scenario.primitives))}
    assert documented <= set(tools) and documented <= set(prim.functions(list(scenario.primitives)))
    assert {"status", "observe", "run_code", "wait", "chat"} <= set(tools)
    assert not tools["status"].acting and not tools["observe"].acting
    assert all(tools[name].acting for name in ("run_code", "wait", "chat", *documented))
    players = scenario.side("red").player_names
    assert tools["observe"].parameters["properties"]["player"]["enum"] == players


def test_every_parameter_the_documentation_names_is_typed():
    names = {name for module in prim.MODULES for p in primitives_of([module]) for name, _ in p.parameters}
    assert names and names <= set(PARAMETERS), sorted(names - set(PARAMETERS))


def test_a_primitive_tool_declares_its_arguments_and_defaults_from_its_signature():
    mine = next(t for t in tools_of(make_scenario("mushroom_war"), "blue") if t.name == "mineBlock")
    schema = mine.parameters
    assert schema["required"] == ["player", "name"] and schema["additionalProperties"] is False
    assert schema["properties"]["count"] == {"type": "integer", "default": 1}
    assert schema["properties"]["point"]["default"] is None
    assert schema["properties"]["player"]["enum"] == ["Byte", "Blink"]
    validator = jsonschema.Draft202012Validator(schema)
    assert not list(validator.iter_errors({"player": "Byte", "name": "blue_mushroom_block", "count": 2}))
    assert list(validator.iter_errors({"player": "Ryn", "name": "x"}))  # not on blue
    assert list(validator.iter_errors({"player": "Byte", "name": "x", "speed": 3}))  # not an argument


def test_a_primitive_call_is_the_line_of_code_it_stands_for():
    by_name = {p.name: p for p in primitives_of(["mineBlock", "useChest"])}
    code = call_code(by_name["mineBlock"], {"name": "slime_block", "maxDistance": 8, "point": [1, 4, -2]})
    assert code.startswith('const returned = await mineBlock(bot, "slime_block", undefined, new Vec3(1, 4, -2), 8)')
    code = call_code(by_name["getItemFromChest"], {"chestPosition": [3, 4, 5], "itemsToGet": {"egg": 2}})
    assert 'await getItemFromChest(bot, new Vec3(3, 4, 5), {"egg": 2})' in code
    assert "save(" in code  # what it returns comes back as the run's onSave event


def test_an_outside_agent_is_its_declared_name_version_and_model():
    def entrant(**options):
        given = {"seat": "seat-1-x", **options}
        config = load_config(["red=agent", "llm.model=gpt-4o", *(f"red.{k}={v}" for k, v in given.items())])
        return entrant_of(RunConfig.of(config), "red")

    one = entrant(agent="claude-code", agent_version="2.1", agent_model="claude-sonnet-4-5")
    assert one.label == "agent:claude-code/2.1@claude-sonnet-4-5"
    assert one.models == {"team": "claude-sonnet-4-5"}
    assert entrant(agent="claude-code", agent_version="2.1", agent_model="claude-sonnet-4-5", seat="other").id == one.id
    others = [
        entrant(agent="codex", agent_version="2.1", agent_model="claude-sonnet-4-5"),
        entrant(agent="claude-code", agent_version="2.2", agent_model="claude-sonnet-4-5"),
        entrant(agent="claude-code", agent_version="2.1"),
    ]
    assert len({one.id, *(e.id for e in others)}) == 4
    assert others[2].label == "agent:claude-code/2.1"
    assert entrant(agent="x", agent_version="1", window_ms=0).label == "agent:x/1(window_ms=0)"
