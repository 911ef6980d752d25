"""The team registry: config name -> Team class, and teams made from their config node.

The built-in teams are registered by `pillagerbench.teams` (the package); a team from outside
registers itself with `register(cls)` before a match is made. Team modules never import the
package or each other (see the import contracts in pyproject.toml).
"""

from __future__ import annotations

from typing import Any

from omegaconf import OmegaConf

from pillagerbench.config import ConfigError
from pillagerbench.teams.base import Team

TEAMS: dict[str, type[Team]] = {}


def register(cls: type[Team]) -> type[Team]:
    """Add a team class under its `name` (usable as a class decorator)."""
    TEAMS[cls.name] = cls
    return cls


def make_team(name: str, scenario_key: str, **options: Any) -> Team:
    if name not in TEAMS:
        raise ConfigError(f"unknown team {name!r}; valid teams: {', '.join(TEAMS)}")
    cls = TEAMS[name]
    if cls.scenarios is not None and scenario_key not in cls.scenarios:
        valid = [n for n, c in TEAMS.items() if c.scenarios is None or scenario_key in c.scenarios]
        raise ConfigError(f"team {name!r} plays only {', '.join(cls.scenarios)}, not {scenario_key}; "
                          f"teams for {scenario_key}: {', '.join(valid)}")
    return cls(**options)


def team_options(team_cfg: Any) -> dict[str, Any]:
    """The team's constructor options: its config node without `name` and `llm`."""
    opts = OmegaConf.to_container(team_cfg, resolve=True)
    assert isinstance(opts, dict)
    opts.pop("name", None)
    opts.pop("llm", None)
    return {str(k): v for k, v in opts.items()}


def team_from_config(team_cfg: Any, scenario_key: str) -> Team:
    """The team a side's config node (`cfg.red`, `cfg.blue`) names, with its options."""
    return make_team(team_cfg.name, scenario_key, **team_options(team_cfg))
