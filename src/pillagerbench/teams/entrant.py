"""The entrant: the unit every table, rating and comparison speaks of (issue 37, docs/experiments.md).

An entrant is a team with its model for each role and the options that change its play:

    {"label": "tacticrafter@gpt-4o(no causal)", "id": "3f2a9c1b7d04",
     "team": "tacticrafter", "models": {"team": "gpt-4o"}, "options": {"causal": false}}

- `team`: the side's team name (`red.name`);
- `models`: for a team that uses an LLM, the side's model (`llm.model` with `red.llm.model` over it)
  under "team", and each role whose own model differs (TactiCrafter's `roles.<role>.model`); {} for a
  team without an LLM;
- `options`: the team's options that differ from its declared defaults (teams/options.py), aliases
  resolved (ALIASES), without those that do not change play (NOT_PLAY) and without role models;
- `label`: readable, `team@model(option, ...)`; a built-in team with its defaults is its name;
- `id`: the first 12 hex digits of the sha256 of the canonical {team, models, options}: the same
  entrant gives the same id in every process and on every machine.

`entrant_of(config, side)` computes it from a run's resolved config: the match records it on every
episode (`red_entrant`, `blue_entrant`), and readers derive it from the series' manifest for records
from before it (metrics/entrants.py). Other LLM settings (provider, temperature of the preset,
endpoint) are not part of the entrant: the model's name is.
"""

from __future__ import annotations

import hashlib
import json
from typing import Any

from pillagerbench.config.sides import SIDES
from pillagerbench.teams.options import defaults, options_model
from pillagerbench.teams.registry import TEAMS

# options that change nothing the team does in the game (they only choose what is written to files)
NOT_PLAY: dict[str, tuple[str, ...]] = {
    "tacticrafter": ("keep_messages",),
    "agent": ("seat", "think_limit_s"),
}

# an option spelled two ways: alias -> the option it sets when not null
ALIASES: dict[str, dict[str, str]] = {
    "tacticrafter": {"enable_causal": "causal", "enable_opponent": "opponent"},
}

# how a switch (a true/false option) reads in a label; any other option reads `key=value`
WORDS: dict[tuple[str, bool], str] = {
    ("causal", False): "no causal",
    ("opponent", False): "no opponent",
    ("update_tactics", False): "fixed tactics",
}

# a team played by an agent from outside (teams/tools/agent.py): it is named by the agent's declared name and
# version, and its model when given (options: name, version, model), not by the team's own name
IDENTITY: dict[str, tuple[str, str, str]] = {"agent": ("agent", "agent_version", "agent_model")}

ROLES_OPTION = "roles"  # an option of per-role settings, each of which may name its own model
LONG = 24  # a string value longer than this reads as `key=#` and 6 hex digits of its hash


def _canonical(value: Any) -> Any:
    """Numbers as JSON would compare them (2.0 and 2 are one value), mappings with sorted keys."""
    if isinstance(value, float) and value.is_integer():
        return int(value)
    if isinstance(value, dict):
        return {str(k): _canonical(v) for k, v in sorted(value.items())}
    if isinstance(value, (list, tuple)):
        return [_canonical(v) for v in value]
    return value


def _digest(value: Any, n: int) -> str:
    text = json.dumps(value, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:n]


def _uses_llm(team: str, node: dict) -> bool:
    cls = TEAMS.get(team)
    return bool(cls.uses_llm) if cls is not None else "llm" in node  # an outside team: it has an llm node


def _options(team: str, node: dict) -> dict[str, Any]:
    """The options that change play and differ from the team's defaults."""
    opts = {k: v for k, v in node.items() if k not in ("name", "llm")}
    for alias, target in ALIASES.get(team, {}).items():
        if opts.get(alias) is not None:
            opts[target] = opts[alias]
        opts.pop(alias, None)
    cls = TEAMS.get(team)
    declared = defaults(options_model(cls)) if cls is not None else {}
    return {
        k: _canonical(v)
        for k, v in sorted(opts.items())
        if k not in NOT_PLAY.get(team, ()) and (k not in declared or _canonical(v) != _canonical(declared[k]))
    }


def _models(config: dict, node: dict, options: dict[str, Any]) -> dict[str, str]:
    """The team's model, and each role's that differs; role models leave `options`."""
    llm = {**(config.get("llm") or {}), **(node.get("llm") or {})}
    model = str(llm.get("model") or "?")
    models = {"team": model}
    roles = options.pop(ROLES_OPTION, None) or {}
    rest = {}
    for role, settings in sorted(roles.items()):
        settings = dict(settings or {})
        own = settings.pop("model", None)
        if own and str(own) != model:
            models[role] = str(own)
        if settings:
            rest[role] = settings
    if rest:
        options[ROLES_OPTION] = rest
    return models


def _word(key: str, value: Any) -> str:
    if isinstance(value, bool) and (key, value) in WORDS:
        return WORDS[(key, value)]
    text = value if isinstance(value, str) else json.dumps(value, sort_keys=True, separators=(",", ":"))
    return f"{key}=#{_digest(value, 6)}" if len(text) > LONG else f"{key}={text}"


def label_of(team: str, models: dict[str, str], options: dict[str, Any]) -> str:
    """`team@model(role=model, option, ...)`; a team without an LLM or options is its name."""
    words = [f"{role}={m}" for role, m in models.items() if role != "team"]
    words += [_word(k, v) for k, v in options.items()]
    at = f"@{models['team']}" if models else ""
    return f"{team}{at}" + (f"({', '.join(words)})" if words else "")


def _agent(team: str, node: dict, options: dict[str, Any]) -> tuple[str, dict[str, str]]:
    """An outside agent's name for the label (`agent:NAME/VERSION`) and its model; the identity's options
    leave `options` but stay in it as the agent's name and version (two agents never share an entrant)."""
    name_key, version_key, model_key = IDENTITY[team]
    options.pop(model_key, None)
    model = node.get(model_key)
    name, version = node.get(name_key) or "unknown", node.get(version_key) or "0"
    options[name_key], options[version_key] = str(name), str(version)
    return f"{team}:{name}/{version}", ({"team": str(model)} if model else {})


def entrant_of(config: dict, side: str) -> dict[str, Any]:
    """The entrant playing `side` ("red" or "blue") under a run's resolved config (a plain dict)."""
    node = dict(config.get(side) or {})
    team = str(node.get("name"))
    options = _options(team, node)
    if team in IDENTITY:
        shown, models = _agent(team, node, options)
        words = {k: v for k, v in options.items() if k not in IDENTITY[team]}
        canonical = {"team": team, "models": models, "options": options}
        return {"label": label_of(shown, models, words), "id": _digest(canonical, 12), **canonical}
    models = _models(config, node, options) if _uses_llm(team, node) else {}
    canonical = {"team": team, "models": models, "options": options}
    return {"label": label_of(team, models, options), "id": _digest(canonical, 12), **canonical}


def labels_of(config: dict) -> dict[str, str]:
    """Each side's entrant label under a run's resolved config: what its records and tables call it."""
    return {side: entrant_of(config, side)["label"] for side in SIDES}
