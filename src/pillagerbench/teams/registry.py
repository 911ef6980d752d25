"""The team registry: every way a team name can be written resolves here.

- a registered name: the built-in teams (registered by the package, `pillagerbench.teams`; team
  modules never import the package or each other), or a class registered with `register(cls)`;
- an entry point of the group `pillagerbench.teams`: installed packages register teams by name;
- an import path `package.module:Class` to a `Team` subclass, from anywhere on the Python path.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass, field
from importlib.metadata import entry_points
from typing import Any

from pillagerbench.config.compose import ConfigError
from pillagerbench.config.registry import Registry
from pillagerbench.config.schema import TeamConfig
from pillagerbench.teams.base import Team
from pillagerbench.teams.options import defaults, options_model

ENTRY_POINT_GROUP = "pillagerbench.teams"
TEAMS: Registry[type[Team]] = Registry("team", hint="(or an import path package.module:Class)")


def register(cls: type[Team]) -> type[Team]:
    """Add a team class under its `name` (a decorator)."""
    return TEAMS.register(cls.name, cls)


@dataclass
class TeamEntry:
    name: str
    cls: type[Team]
    source: str  # built-in | entry point <distribution> | import path
    options: dict[str, Any] = field(default_factory=dict)


def declared_options(name: str, cls: type[Team] | None = None) -> dict[str, Any]:
    """The options a team declares, with their defaults (without name and llm): its options model
    (`Team.Options`, or `options_declared`; teams/options.py)."""
    return defaults(options_model(cls if cls is not None else find_team(name)))


def _entry_points() -> dict[str, list]:
    found: dict[str, list] = {}
    for ep in entry_points(group=ENTRY_POINT_GROUP):
        found.setdefault(ep.name, []).append(ep)
    return found


def _checked(cls: Any, where: str) -> type[Team]:
    if not (isinstance(cls, type) and issubclass(cls, Team)):
        raise ConfigError(
            f"{where} is {cls!r}, not a team: it must be a subclass of pillagerbench.teams.Team (docs/your-team.md)"
        )
    return cls


def _from_entry_point(name: str, eps: list) -> type[Team]:
    if len(eps) > 1 or name in TEAMS:
        owners = [f"entry point {ep.value}" for ep in eps] + (["the built-in team"] if name in TEAMS else [])
        raise ConfigError(
            f"two teams are registered under the name {name!r} ({'; '.join(owners)}): "
            f"uninstall one, or name the class by import path (module:Class)"
        )
    ep = eps[0]
    try:
        cls = ep.load()
    except Exception as exc:  # noqa: BLE001 - whatever an outside package raises on import
        raise ConfigError(
            f"team {name!r}: its entry point {ep.value} failed to import: "
            f"{type(exc).__name__}: {exc} (fix or reinstall that package)"
        ) from None
    return _checked(cls, f"team {name!r} (entry point {ep.value})")


def _from_import_path(path: str) -> type[Team]:
    module_name, _, attr = path.partition(":")
    if not module_name or not attr:
        raise ConfigError(f"team {path!r}: an import path is package.module:Class")
    try:
        module = importlib.import_module(module_name)
    except Exception as exc:  # noqa: BLE001 - whatever an outside module raises on import
        raise ConfigError(
            f"team {path!r}: cannot import {module_name}: {type(exc).__name__}: {exc} "
            "(is it installed, or on PYTHONPATH?)"
        ) from None
    try:
        cls = getattr(module, attr)
    except AttributeError:
        raise ConfigError(f"team {path!r}: module {module_name} has no {attr}") from None
    return _checked(cls, f"team {path!r}")


def find_team(name: str) -> type[Team]:
    """The class for a team name, entry point name or import path; ConfigError naming the fix."""
    eps = _entry_points()
    if name in eps:
        return _from_entry_point(name, eps[name])
    if ":" in name and name not in TEAMS:
        return _from_import_path(name)
    return TEAMS.find(name, also=sorted(eps))


def available() -> list[TeamEntry]:
    """Every team a name can reach: registered ones, then entry points (import path teams are not listed)."""
    out = [TeamEntry(n, c, "built-in", declared_options(n, c)) for n, c in TEAMS.items()]
    for name, eps in sorted(_entry_points().items()):
        try:
            cls = _from_entry_point(name, eps)
            out.append(TeamEntry(name, cls, f"entry point {eps[0].value}", declared_options(name, cls)))
        except ConfigError as exc:
            out.append(TeamEntry(name, Team, f"broken: {exc}"))
    return out


def make_team(name: str, scenario_key: str, **options: Any) -> Team:
    cls = find_team(name)
    if cls.scenarios is not None and scenario_key not in cls.scenarios:
        valid = [n for n, c in TEAMS.items() if c.scenarios is None or scenario_key in c.scenarios]
        raise ConfigError(
            f"team {name!r} plays only {', '.join(cls.scenarios)}, not {scenario_key}; "
            f"teams for {scenario_key}: {', '.join(valid)}"
        )
    return cls(**options)


def team_from_config(team_cfg: TeamConfig, scenario_key: str) -> Team:
    """The team a side's config node (`cfg.red`, `cfg.blue`) names, with its options."""
    return make_team(team_cfg.name, scenario_key, **team_cfg.options)
