"""Each team declares its options once: its options model (`Team.Options`, teams/options.py), with
types, ranges, defaults and a one-line description each. A built-in team's conf/team/<name>.yaml
(Hydra selects `red=NAME` by file) repeats them: these tests fail when a key, its order, a default
(value or type) or a description differs, and print the lines the file should have. Validation of
`red.KEY=VALUE` uses the model. No server needed."""

from __future__ import annotations

import inspect
import re
from importlib import resources

import pytest
from omegaconf import OmegaConf

from pillagerbench.config.compose import config_options, load_config, team_yaml_options
from pillagerbench.config.validate import team_problems
from pillagerbench.teams import BUILT_IN, TEAMS
from pillagerbench.teams.options import defaults, options_model, yaml_lines

YAML_TEAMS = config_options("team")
OPTION_LINE = re.compile(r"^(\w+):\s*(.*?)\s*(?:#\s*(.*))?$")


def yaml_comments(name: str) -> dict[str, str]:
    """The comment of each option line of conf/team/<name>.yaml."""
    text = (resources.files("pillagerbench.conf") / "team" / f"{name}.yaml").read_text()
    found = (OPTION_LINE.match(line) for line in text.splitlines())
    return {m.group(1): m.group(3) or "" for m in found if m and m.group(1) not in ("name", "llm", "defaults")}


def test_every_yaml_file_is_a_built_in_team_and_every_built_in_team_but_remote_and_agent_has_one():
    assert sorted(YAML_TEAMS) == sorted(c.name for c in BUILT_IN if c.name not in ("remote", "agent"))


@pytest.mark.parametrize("name", YAML_TEAMS)
def test_the_yaml_file_repeats_the_model(name):
    model = options_model(TEAMS[name])
    yaml, declared = team_yaml_options(name), defaults(model)
    assert yaml is not None
    hint = f"conf/team/{name}.yaml should list, after `name:`,\n" + "\n".join(yaml_lines(model))
    assert list(yaml) == list(declared), hint  # the same keys in the same order
    for key, value in declared.items():
        assert (yaml[key], type(yaml[key])) == (value, type(value)), (
            f"{key}: YAML {yaml[key]!r}, model {value!r}\n{hint}"
        )
    assert yaml_comments(name) == {k: f.description for k, f in model.model_fields.items()}, hint


@pytest.mark.parametrize("cls", BUILT_IN, ids=lambda c: c.name)
def test_options_are_declared_once_with_a_one_line_description(cls):
    for key, field in options_model(cls).model_fields.items():
        assert field.description and "\n" not in field.description, key
    # the constructor keeps no defaults of its own: it reads its options through the model
    params = [p for n, p in inspect.signature(cls.__init__).parameters.items() if n != "self"]
    assert all(p.kind is p.VAR_KEYWORD for p in params), params


@pytest.mark.parametrize("cls", [c for c in BUILT_IN if options_model(c).model_fields], ids=lambda c: c.name)
def test_a_team_built_without_options_has_the_models_defaults(cls):
    team = cls()
    model = options_model(cls)
    assert model.model_validate(team.options).model_dump() == defaults(model)
    with pytest.raises(ValueError, match="bogus"):
        cls(bogus=1)


@pytest.mark.parametrize(
    "overrides, line",
    [
        (["red=random", "red.pause_every=0"], "red.pause_every=0: input should be greater than or equal to 1"),
        (["red=cot", "red.temperature=5"], "red.temperature=5: input should be less than or equal to 2"),
        (["red=random", "red.action_timeout_s=2.5"], None),  # a float, as the constructor takes (YAML had 20)
        (["red=tacticrafter", "red.checkpoint=runs/x"], None),
        (
            ["red=remote", "red.url=http://127.0.0.1:1", "red.bogus=1"],
            "red.bogus: unknown key (options of remote: url,",
        ),
        (["red=remote", "red.url=http://127.0.0.1:1", "red.call_timeout_s=0"], "red.call_timeout_s=0: input should be"),
    ],
)
def test_validation_uses_the_model(overrides, line):
    found = team_problems(load_config(overrides))
    if line is None:
        assert found == []
    else:
        assert any(p.startswith(line) for p in found), found


def test_tacticrafters_roles_are_checked_before_the_run():
    cfg = load_config(["red=tacticrafter"])
    OmegaConf.set_struct(cfg, False)
    cfg.red.roles = {"chef": {}, "action": {"temprature": 0.0}}
    [line] = team_problems(cfg)
    assert line.startswith(
        "red.roles={'chef': {}, 'action': {'temprature': 0.0}}: value error, tacticrafter: unknown role"
    )


@pytest.mark.parametrize(
    ("overrides", "red_cap", "blue_cap"),
    [
        (["red=cot", "blue=cot"], 4096, 4096),  # the preset's own 512 does not cut a team's cap
        (["red=cot", "blue=cot", "llm.max_tokens=1024"], 1024, 1024),  # the user's limit wins: stricter
        (["red=cot", "blue=cot", "llm.max_tokens=9000"], 4096, 4096),  # the team's cap is stricter
        (["red=cot", "blue=cot", "blue.llm.max_tokens=100"], 4096, 100),  # one side's limit
        (["red=cot", "blue=tools", "red.max_tokens=8000", "llm.max_tokens=1024"], 1024, 1024),
    ],
)
def test_the_users_llm_max_tokens_caps_a_teams_own_answer_cap(overrides, red_cap, blue_cap):
    cfg = load_config(overrides)
    assert (cfg.red.max_tokens, cfg.blue.max_tokens) == (red_cap, blue_cap)
