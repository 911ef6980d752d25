"""The run config of one league match, the checks of an entrant and its identity, from league.yaml's entries.

An entrant's team options go to its side (`red.KEY`); its LLM (a preset plus options) becomes its
side's own `llm` node (`red.llm`), so two LLM entrants with different models can meet. The entrant a
roster entry plays as (`entrant_of_entry`: rundir/entrant.py's type, whose id a round's league.json
stamps) is read from the config composed for it on red against do_nothing, without game overrides (the
stamp keeps those apart): the same entrant its episodes record."""

from __future__ import annotations

import json
from dataclasses import asdict
from functools import cache

from pillagerbench.config.compose import ConfigError
from pillagerbench.config.schema import LLMKeys, RunConfig
from pillagerbench.config.validate import check_run_config, compose_run, llm_preset
from pillagerbench.league.spec import DEFAULT_SCENARIOS, RosterEntry
from pillagerbench.rundir.entrant import Entrant
from pillagerbench.teams import find_team
from pillagerbench.teams.entrant import entrant_of

OPPONENT = RosterEntry(name="do_nothing", team="do_nothing")  # the side an entry is composed against


@cache
def _preset(name: str) -> LLMKeys:
    return llm_preset(name)


def _side(cfg: RunConfig, side: str, entrant: RosterEntry) -> RunConfig:
    cfg = cfg.updated({side: entrant.options})
    if entrant.llm or entrant.llm_options:
        own = _preset(entrant.llm) if entrant.llm else LLMKeys()
        cfg = cfg.with_llm(side, own.over(LLMKeys.of(entrant.llm_options, f"{side}.llm")))
    return cfg


def match_config(scenario: str, red: RosterEntry, blue: RosterEntry, game: tuple[str, ...] = ()) -> RunConfig:
    """The full config of a match (checked: one ConfigError line per problem)."""
    cfg = compose_run([*game, f"scenario={scenario}", f"red={red.team}", f"blue={blue.team}"])
    return check_run_config(_side(_side(cfg, "red", red), "blue", blue), teams=True).for_series()


def playable(entrant: RosterEntry, scenarios: list[str]) -> list[str]:
    """The league scenarios the entrant's team can play (ConfigError if the team does not exist)."""
    cls = find_team(entrant.team)
    return [s for s in scenarios if cls.scenarios is None or s in cls.scenarios]


def check_entrant(entrant: RosterEntry, scenarios: list[str], game: tuple[str, ...] = ()) -> None:
    """ConfigError (one line) when the entrant cannot play in this league."""
    try:
        where = playable(entrant, scenarios)
    except ConfigError as exc:
        raise ConfigError(f"entrant {entrant.name!r}: {exc}") from None
    if not where:
        raise ConfigError(
            f"entrant {entrant.name!r}: team {entrant.team} plays none of the league's scenarios "
            f"({', '.join(scenarios)}); it plays {', '.join(find_team(entrant.team).scenarios or [])}"
        )
    try:
        cfg = match_config(where[0], entrant, OPPONENT, game)
    except ConfigError as exc:
        first = str(exc).splitlines()[0]
        if first.startswith("red"):  # the entrant played red in the checked config
            first = "team" + first[3:]
        raise ConfigError(f"entrant {entrant.name!r}: {first}") from None
    if seated := cfg.seated():
        raise ConfigError(
            f"entrant {entrant.name!r}: people would play {' and '.join(seated)} (team human or humans=): a league "
            "schedules and plays its matches itself and cannot seat people; play a person's matches with "
            "`pillagerbench run` and read them with `pillagerbench report` (docs/people.md)"
        )


def entrant_of_entry(entry: RosterEntry) -> Entrant:
    """The entrant a roster entry plays as (its name aside): ConfigError (one line) when it cannot play."""
    key = asdict(entry)
    key.pop("name")
    try:
        return _entrant(json.dumps(key, sort_keys=True, default=str))
    except ConfigError as exc:
        raise ConfigError(f"entrant {entry.name!r}: {str(exc).splitlines()[0]}") from None


@cache
def _entrant(key: str) -> Entrant:
    entry = RosterEntry(name="", **json.loads(key))
    scenario = (find_team(entry.team).scenarios or DEFAULT_SCENARIOS)[0]  # any scenario: none changes a side
    return entrant_of(match_config(scenario, entry, OPPONENT), "red")
