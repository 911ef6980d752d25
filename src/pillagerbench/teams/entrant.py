"""An entrant from a run's config (issue 37, docs/experiments.md): the type, its label and its id are
rundir/entrant.py's `Entrant`; this module reads one side of a resolved config into it, with what only
the teams know (each team's declared option defaults, teams/options.py):

- `team`: the side's team name (`red.name`);
- `models`: for a team that uses an LLM, the side's model (`llm.model` with `red.llm.model` over it)
  under "team", and each role whose own model differs (TactiCrafter's `roles.<role>.model`); {} for a
  team without an LLM; a team played by an agent from outside has the agent's model (IDENTITY);
- `options`: the team's options that differ from its declared defaults, aliases resolved (ALIASES),
  without those that do not change play (NOT_PLAY) and without role models.

`entrant_of(config, side)` computes it: the match records it on every episode (`red_entrant`,
`blue_entrant`), readers derive it from the series' manifest for records from before it
(metrics/entrants.py), and the league's identity of an entrant is its id (league/compose.py). Other LLM
settings (provider, temperature of the preset, endpoint) are not part of the entrant: the model's name is.
"""

from __future__ import annotations

from typing import Any

from pillagerbench.config.schema import Choices, LLMKeys, RunConfig, TeamConfig
from pillagerbench.config.sides import SIDES
from pillagerbench.rundir.entrant import IDENTITY, Entrant, canonical
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

ROLES_OPTION = "roles"  # an option of per-role settings, each of which may name its own model


def _uses_llm(team: str, node: TeamConfig) -> bool:
    cls = TEAMS.get(team)
    return (
        bool(cls.uses_llm) if cls is not None else "llm" in node.model_fields_set
    )  # an outside team: it has an llm node


def _options(team: str, node: TeamConfig) -> dict[str, Any]:
    """The options that change play and differ from the team's defaults."""
    opts = node.options
    for alias, target in ALIASES.get(team, {}).items():
        if opts.get(alias) is not None:
            opts[target] = opts[alias]
        opts.pop(alias, None)
    cls = TEAMS.get(team)
    declared = defaults(options_model(cls)) if cls is not None else {}
    return {
        k: canonical(v)
        for k, v in sorted(opts.items())
        if k not in NOT_PLAY.get(team, ()) and (k not in declared or canonical(v) != canonical(declared[k]))
    }


def _models(llm: LLMKeys, options: dict[str, Any]) -> dict[str, str]:
    """The team's model (of `llm`, the settings the side plays with), and each role's that differs; role
    models leave `options`."""
    model = str(llm.model or "?")
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


def _agent(team: str, node: TeamConfig, options: dict[str, Any]) -> dict[str, str]:
    """An outside agent's model; the identity's options leave `options` but stay in it as the agent's name
    and version (two agents never share an entrant; its label is `agent:NAME/VERSION`)."""
    name_key, version_key, model_key = IDENTITY[team]
    given = node.options
    options.pop(model_key, None)
    model = given.get(model_key)
    options[name_key], options[version_key] = str(given.get(name_key) or "unknown"), str(given.get(version_key) or "0")
    return {"team": str(model)} if model else {}


def entrant_of(config: Choices | RunConfig, side: str) -> Entrant:
    """The entrant playing `side` ("red" or "blue") under a run's configuration."""
    node = config.side(side)
    team = node.name
    options = _options(team, node)
    if team in IDENTITY:
        return Entrant(team, _agent(team, node, options), options)
    return Entrant(team, _models(config.llm_of(side), options) if _uses_llm(team, node) else {}, options)


def labels_of(config: Choices | RunConfig) -> dict[str, str]:
    """Each side's entrant label under a run's resolved config: what its records and tables call it."""
    return {side: entrant_of(config, side).label for side in SIDES}
