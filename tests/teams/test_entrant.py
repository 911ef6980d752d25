"""The entrant (rundir/entrant.py, read from a run's config by teams/entrant.py): a team with its model for
each role and the options that change its play; its label reads as `team@model(options)` and its id is the
same in every process, and the same as the records written before the type (their dicts load as they are)."""

from __future__ import annotations

import dataclasses
import json
import subprocess
import sys

import pytest

from pillagerbench.config.compose import load_config
from pillagerbench.config.schema import RunConfig
from pillagerbench.rundir import EpisodeRecord
from pillagerbench.rundir.entrant import Entrant
from pillagerbench.teams.entrant import entrant_of

# overrides -> (label, id) as teams/entrant.py computed them before the type (the dicts records hold)
BEFORE = {
    ("red=cot", "red.llm.model=gpt-4o"): ("cot@gpt-4o", "adb0ba297d3b"),
    ("red=cot", "llm.model=gpt-4o-mini"): ("cot@gpt-4o-mini", "fded8e2093ad"),
    ("red=tacticrafter", "red.llm.model=gpt-4o", "red.causal=false"): (
        "tacticrafter@gpt-4o(no causal)",
        "edcfeba1a2a9",
    ),
    ("red=tacticrafter", "red.llm.model=gpt-4o", "red.enable_causal=false"): (
        "tacticrafter@gpt-4o(no causal)",
        "edcfeba1a2a9",
    ),
    ("red=random", "red.pause_s=2.0"): ("random(pause_s=2)", "dc96b044d417"),
    ("red=tacticrafter", "llm.model=gpt-4o", "+red.roles.critic.model=gpt-4o-mini"): (
        "tacticrafter@gpt-4o(critic=gpt-4o-mini)",
        "ff6f7ecf2546",
    ),
    ("red=tacticrafter", "red.llm.model=gpt-4o", "red.opponent=false"): (
        "tacticrafter@gpt-4o(no opponent)",
        "ac7b287d6b5b",
    ),
    ("red=agent", "red.agent=react", "red.agent_version=0.3", "red.agent_model=mockllm/model"): (
        "agent:react/0.3@mockllm/model",
        "7d3bb863808c",
    ),
    ("red=balanced",): ("balanced", "bb80ae923150"),
}


def red(*overrides: str) -> Entrant:
    return entrant_of(RunConfig.of(load_config(["llm=openai", *overrides])), "red")


@pytest.mark.parametrize("overrides", list(BEFORE), ids=[" ".join(o) for o in BEFORE])
def test_the_label_and_id_are_those_records_hold(overrides):
    entrant = red(*overrides)
    assert (entrant.label, entrant.id) == BEFORE[overrides]
    written = entrant.to_dict()
    assert list(written) == ["label", "id", "team", "models", "options"]  # the record's dict, as written before
    assert Entrant.from_dict(json.loads(json.dumps(written))) == entrant
    assert Entrant.from_dict(json.loads(json.dumps(written))).to_dict() == written


def test_one_team_on_two_models_is_two_entrants():
    four, mini = red("red=cot", "red.llm.model=gpt-4o"), red("red=cot", "llm.model=gpt-4o-mini")
    assert (four.label, mini.label) == ("cot@gpt-4o", "cot@gpt-4o-mini")
    assert four.id != mini.id and four != mini and len({four, mini}) == 2
    assert four.models == {"team": "gpt-4o"} and four.options == {}


def test_a_built_in_team_is_its_name_and_the_other_side_is_its_own_entrant():
    cfg = RunConfig.of(load_config(["red=balanced", "blue=passive"]))
    assert entrant_of(cfg, "red").label == "balanced" and entrant_of(cfg, "red").models == {}
    assert entrant_of(cfg, "blue").label == "passive"


def test_play_options_name_the_entrant_and_the_others_do_not():
    full = red("red=tacticrafter", "red.llm.model=gpt-4o")
    no_causal = red("red=tacticrafter", "red.llm.model=gpt-4o", "red.causal=false")
    alias = red("red=tacticrafter", "red.llm.model=gpt-4o", "red.enable_causal=false")  # upstream's name
    quiet = red("red=tacticrafter", "red.llm.model=gpt-4o", "red.keep_messages=false")  # only what is written
    assert full.label == "tacticrafter@gpt-4o"
    assert no_causal.label == "tacticrafter@gpt-4o(no causal)" and no_causal.options == {"causal": False}
    assert alias == no_causal
    assert quiet == full
    tuned = red("red=random", "red.pause_s=2.0")
    assert tuned.label == "random(pause_s=2)" and tuned.id == red("red=random", "red.pause_s=2").id


def test_a_role_on_its_own_model_is_in_the_entrant():
    critic = red("red=tacticrafter", "llm.model=gpt-4o", "+red.roles.critic.model=gpt-4o-mini")
    same = red("red=tacticrafter", "llm.model=gpt-4o", "+red.roles.critic.model=gpt-4o")
    assert critic.models == {"team": "gpt-4o", "critic": "gpt-4o-mini"}
    assert critic.label == "tacticrafter@gpt-4o(critic=gpt-4o-mini)"
    assert same == red("red=tacticrafter", "llm.model=gpt-4o")


def test_the_entrant_is_frozen_and_hashes_as_its_id():
    entrant = red("red=cot", "red.llm.model=gpt-4o")
    with pytest.raises(dataclasses.FrozenInstanceError):
        entrant.team = "balanced"  # type: ignore[misc]
    assert hash(entrant) == hash(entrant.id)
    again = Entrant("cot", {"team": "gpt-4o"}, {})
    assert again == entrant and {entrant: 1}[again] == 1
    assert Entrant("cot", {"team": "gpt-4o"}, {"x": 1}) != entrant


def test_a_record_keeps_its_entrants_dicts_and_an_old_one_loads():
    written = {  # an episode line as written before the type: the entrants are dicts
        "scenario": "mushroom_war",
        "red": "cot",
        "blue": "balanced",
        "episode": 0,
        "red_entrant": {
            "label": "cot@gpt-4o",
            "id": "adb0ba297d3b",
            "team": "cot",
            "models": {"team": "gpt-4o"},
            "options": {},
        },
        "blue_entrant": {"label": "balanced", "id": "bb80ae923150", "team": "balanced", "models": {}, "options": {}},
    }
    rec = EpisodeRecord.from_dict(written)
    assert isinstance(rec.red_entrant, Entrant) and (rec.red_entrant.label, rec.red_entrant.id) == (
        "cot@gpt-4o",
        "adb0ba297d3b",
    )
    assert rec.to_dict()["red_entrant"] == written["red_entrant"]
    assert rec.to_dict()["blue_entrant"] == written["blue_entrant"]
    assert EpisodeRecord.from_dict(json.loads(json.dumps(rec.to_dict()))) == rec
    older = EpisodeRecord.from_dict({k: v for k, v in written.items() if not k.endswith("_entrant")})
    assert older.red_entrant is None and older.to_dict()["red_entrant"] is None  # before entrants: derived by readers


def test_the_id_is_the_same_in_another_process():
    overrides = ["llm=openai", "red=tacticrafter", "red.llm.model=gpt-4o", "red.opponent=false"]
    code = (
        "import json, sys; from pillagerbench.config.compose import load_config; "
        "from pillagerbench.config.schema import RunConfig; "
        "from pillagerbench.teams.entrant import entrant_of; "
        "print(json.dumps(entrant_of(RunConfig.of(load_config(sys.argv[1:])), 'red').to_dict()))"
    )
    out = subprocess.run([sys.executable, "-c", code, *overrides], capture_output=True, text=True, check=True)
    theirs = json.loads(out.stdout)
    assert theirs == entrant_of(RunConfig.of(load_config(overrides)), "red").to_dict()
    assert theirs["label"] == "tacticrafter@gpt-4o(no opponent)" and len(theirs["id"]) == 12
