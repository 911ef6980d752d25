"""The one validation of a run's configuration: the command line and conf/ composed (compose.py), typed
(schema.py `RunConfig`) and checked whole, once, before anything is created or started. Every problem is
one line naming the key, the bad value and what is valid; a ConfigError holds all of them.

The top-level keys are this package's (schema.py); the groups a configuration chooses by name (the
scenario and its layouts; each side's team, its options and the LLM it plays with) are known to the
layers that hold their registries, above this one. Each such check is registered here by its group's
name (`GROUP_CHECKS`; match/validate.py registers them, and importing `pillagerbench.match` does) and
takes the choices typed (`Choices`), never the composed configuration; a run is refused, not half
checked, when one is missing.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, Final

from pillagerbench.config.compose import load_config
from pillagerbench.config.registry import Registry
from pillagerbench.config.schema import (
    Choices,
    LLMKeys,
    RunConfig,
    ServerConfig,
    check,
    clock_problems,
    plain,
    problems,
    top_level_problems,
    watch_problems,
)

GroupCheck = Callable[[Choices], list[str]]
# the checks of the groups a run chooses, registered by the layer that knows each group's registry
GROUP_CHECKS: Registry[GroupCheck] = Registry("configuration group check")
SCENARIO, LAYOUT, TEAMS = "scenario", "layout", "teams"  # the scenario; layout= and split=; both sides
GROUPS: Final = (SCENARIO, LAYOUT, TEAMS)


def group_problems(cfg: Choices | RunConfig | Any, *groups: str) -> list[str]:
    """The problems the named groups' checks find in `cfg` (typed, or a composed configuration), each line
    once, in the groups' order."""
    missing = [g for g in groups if g not in GROUP_CHECKS]
    if missing:  # a programming error: the run would be played half checked
        raise RuntimeError(
            f"no check of the configuration group(s) {missing} is registered: import pillagerbench.match"
        )
    choices = cfg.choices() if isinstance(cfg, RunConfig) else cfg if isinstance(cfg, Choices) else _choices(cfg)
    found: list[str] = []
    for group in groups:
        found += [p for p in GROUP_CHECKS[group](choices) if p not in found]
    return found


def team_problems(cfg: Choices | RunConfig | Any) -> list[str]:
    """Problems of a match config's scenario and both sides (teams, options, LLM settings)."""
    return group_problems(cfg, SCENARIO, TEAMS)


def layout_problems(cfg: Choices | RunConfig | Any) -> list[str]:
    """`layout=` and `split=`: a known value, one or the other, and a layout of the chosen scenario."""
    return group_problems(cfg, LAYOUT)


def _choices(composed: Any) -> Choices:
    """The choices of a composed configuration (a DictConfig or a mapping), or its problems."""
    data = plain(composed)
    check(problems(Choices, data))
    return Choices.model_validate(data)


def is_experiment(data: Any) -> bool:
    """Whether a composed configuration runs an experiment (or resumes a run): its series choose their teams."""
    data = plain(data)
    return data.get("experiment") is not None or bool(data.get("resume"))


def check_run_config(cfg: Any, *, teams: bool | None = None) -> RunConfig:
    """The typed configuration of `cfg` (a composed configuration, or a RunConfig), or one ConfigError
    listing every problem of it (one line each). Teams are checked unless `teams` is False, or (None) the
    configuration is an experiment's or a resumed run's: their series choose teams themselves (each is
    checked with `team_problems` before it starts, experiments/runner.check_series)."""
    data = cfg.stored() if isinstance(cfg, RunConfig) else plain(cfg)
    teams = not is_experiment(data) if teams is None else teams
    top = top_level_problems(data)
    watch = [] if any(line.startswith("watch=") for line in top) else watch_problems(data)
    if not teams and data.get("watch") is not None:  # an experiment: many servers at once
        watch = [f"watch={data['watch']}: the live view shows one match; experiments play many series at once"]
    groups = (LAYOUT, SCENARIO, TEAMS) if teams else (LAYOUT,)
    chosen = [] if problems(Choices, data) else group_problems(Choices.model_validate(data), *groups)
    check(top + watch + clock_problems(data) + chosen)
    return RunConfig.of(data)


def load_run(argv: Sequence[str], *, teams: bool | None = None) -> RunConfig:
    """The command line's configuration (overrides on conf/), composed, typed and checked whole."""
    return check_run_config(load_config(list(argv)), teams=teams)


def compose_run(argv: Sequence[str]) -> RunConfig:
    """The command line's configuration typed, its top-level keys checked and its groups not yet: a base
    that is changed (RunConfig.updated) before `check_run_config` checks it whole (a league's match)."""
    data = plain(load_config(list(argv)))
    check(top_level_problems(data))
    return RunConfig.of(data)


def load_server(argv: Sequence[str]) -> tuple[ServerConfig, int | None]:
    """`pillagerbench server`: the command line's server keys and `watch=` port, checked."""
    data = plain(load_config(list(argv)))
    check(problems(ServerConfig, data.get("server"), "server") + watch_problems(data))
    return ServerConfig.model_validate(data["server"]), data.get("watch")


def llm_preset(name: str) -> LLMKeys:
    """The settings of the LLM preset `name` (conf/llm/NAME.yaml), as composed."""
    return LLMKeys.of(load_config([f"llm={name}"]).llm)
