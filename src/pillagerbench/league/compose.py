"""The run config of one league match, and the checks of an entrant, from league.yaml's entries.

An entrant's team options go to its side (`red.KEY`); its LLM (a preset plus options) becomes its
side's own `llm` node (`red.llm`), so two LLM entrants with different models can meet."""

from __future__ import annotations

from functools import cache
from typing import Any

from pillagerbench.config.compose import ConfigError, load_config, to_dict
from pillagerbench.config.schema import RunConfig, merged
from pillagerbench.experiments.spec import RUNNER_KEYS
from pillagerbench.league.spec import Entrant
from pillagerbench.match.validate import check_run_config
from pillagerbench.teams import find_team


@cache
def _preset(name: str) -> dict[str, Any]:
    return to_dict(load_config([f"llm={name}"]).llm)


def _side(cfg: dict[str, Any], side: str, entrant: Entrant) -> None:
    cfg[side] = merged(cfg[side], entrant.options)
    if entrant.llm or entrant.llm_options:
        own = _preset(entrant.llm) if entrant.llm else {}
        cfg[side]["llm"] = merged(own, entrant.llm_options)


def match_config(scenario: str, red: Entrant, blue: Entrant, game: tuple[str, ...] = ()) -> RunConfig:
    """The full config of a match (checked: one ConfigError line per problem)."""
    cfg = to_dict(load_config([*game, f"scenario={scenario}", f"red={red.team}", f"blue={blue.team}"]))
    _side(cfg, "red", red)
    _side(cfg, "blue", blue)
    check_run_config(cfg)
    return RunConfig.of({k: v for k, v in cfg.items() if k not in RUNNER_KEYS})


def playable(entrant: Entrant, scenarios: list[str]) -> list[str]:
    """The league scenarios the entrant's team can play (ConfigError if the team does not exist)."""
    cls = find_team(entrant.team)
    return [s for s in scenarios if cls.scenarios is None or s in cls.scenarios]


def check_entrant(entrant: Entrant, scenarios: list[str], game: tuple[str, ...] = ()) -> None:
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
    opponent = Entrant(name="do_nothing", team="do_nothing")
    try:
        match_config(where[0], entrant, opponent, game)
    except ConfigError as exc:
        first = str(exc).splitlines()[0]
        if first.startswith("red"):  # the entrant played red in the checked config
            first = "team" + first[3:]
        raise ConfigError(f"entrant {entrant.name!r}: {first}") from None
