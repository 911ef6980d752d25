"""The entrant (teams/entrant.py): a team with its model for each role and the options that change its
play, read from a run's resolved config; its label reads as `team@model(options)` and its id is the
same in every process."""

from __future__ import annotations

import json
import subprocess
import sys

from pillagerbench.config.compose import load_config, to_dict
from pillagerbench.teams.entrant import entrant_of


def red(*overrides: str) -> dict:
    return entrant_of(to_dict(load_config(["llm=openai", *overrides])), "red")


def test_one_team_on_two_models_is_two_entrants():
    four, mini = red("red=cot", "red.llm.model=gpt-4o"), red("red=cot", "llm.model=gpt-4o-mini")
    assert (four["label"], mini["label"]) == ("cot@gpt-4o", "cot@gpt-4o-mini")
    assert four["id"] != mini["id"]
    assert four["models"] == {"team": "gpt-4o"} and four["options"] == {}


def test_a_built_in_team_is_its_name_and_the_other_side_is_its_own_entrant():
    cfg = to_dict(load_config(["red=balanced", "blue=passive"]))
    assert entrant_of(cfg, "red")["label"] == "balanced" and entrant_of(cfg, "red")["models"] == {}
    assert entrant_of(cfg, "blue")["label"] == "passive"


def test_play_options_name_the_entrant_and_the_others_do_not():
    full = red("red=tacticrafter", "red.llm.model=gpt-4o")
    no_causal = red("red=tacticrafter", "red.llm.model=gpt-4o", "red.causal=false")
    alias = red("red=tacticrafter", "red.llm.model=gpt-4o", "red.enable_causal=false")  # upstream's name
    quiet = red("red=tacticrafter", "red.llm.model=gpt-4o", "red.keep_messages=false")  # only what is written
    assert full["label"] == "tacticrafter@gpt-4o"
    assert no_causal["label"] == "tacticrafter@gpt-4o(no causal)" and no_causal["options"] == {"causal": False}
    assert alias == no_causal
    assert quiet == full
    tuned = red("red=random", "red.pause_s=2.0")
    assert tuned["label"] == "random(pause_s=2)" and tuned["id"] == red("red=random", "red.pause_s=2")["id"]


def test_a_role_on_its_own_model_is_in_the_entrant():
    critic = red("red=tacticrafter", "llm.model=gpt-4o", "+red.roles.critic.model=gpt-4o-mini")
    same = red("red=tacticrafter", "llm.model=gpt-4o", "+red.roles.critic.model=gpt-4o")
    assert critic["models"] == {"team": "gpt-4o", "critic": "gpt-4o-mini"}
    assert critic["label"] == "tacticrafter@gpt-4o(critic=gpt-4o-mini)"
    assert same == red("red=tacticrafter", "llm.model=gpt-4o")


def test_the_id_is_the_same_in_another_process():
    overrides = ["llm=openai", "red=tacticrafter", "red.llm.model=gpt-4o", "red.opponent=false"]
    code = (
        "import json, sys; from pillagerbench.config.compose import load_config, to_dict; "
        "from pillagerbench.teams.entrant import entrant_of; "
        "print(json.dumps(entrant_of(to_dict(load_config(sys.argv[1:])), 'red')))"
    )
    out = subprocess.run([sys.executable, "-c", code, *overrides], capture_output=True, text=True, check=True)
    theirs = json.loads(out.stdout)
    assert theirs == entrant_of(to_dict(load_config(overrides)), "red")
    assert theirs["label"] == "tacticrafter@gpt-4o(no opponent)" and len(theirs["id"]) == 12
