"""Teams (multi-agent systems) by config name."""

from __future__ import annotations

from pillagerbench.config import ConfigError
from pillagerbench.teams.base import Team, TeamContext
from pillagerbench.teams.dash_and_dine import Berries, CakeBeetroot, MelonPumpkin, PotatoCookie
from pillagerbench.teams.do_nothing import DoNothing
from pillagerbench.teams.mushroom_war import Aggressive, Balanced, Passive, Slimy

TEAMS: dict[str, type[Team]] = {cls.name: cls for cls in (
    DoNothing, Aggressive, Balanced, Passive, Slimy, Berries, CakeBeetroot, MelonPumpkin, PotatoCookie)}


def register(cls: type[Team]) -> type[Team]:
    """Add a team class (LLM teams register themselves here)."""
    TEAMS[cls.name] = cls
    return cls


def make_team(name: str, scenario_key: str, **options) -> Team:
    if name not in TEAMS:
        raise ConfigError(f"unknown team {name!r}; valid teams: {', '.join(TEAMS)}")
    cls = TEAMS[name]
    if cls.scenarios is not None and scenario_key not in cls.scenarios:
        valid = [n for n, c in TEAMS.items() if c.scenarios is None or scenario_key in c.scenarios]
        raise ConfigError(f"team {name!r} plays only {', '.join(cls.scenarios)}, not {scenario_key}; "
                          f"teams for {scenario_key}: {', '.join(valid)}")
    return cls(**options)


__all__ = ["TEAMS", "Team", "TeamContext", "make_team", "register"]

from pillagerbench.teams import cot, random_team  # noqa: E402,F401  (baselines; they register themselves)
from pillagerbench.teams import tacticrafter  # noqa: E402,F401  (the paper's TactiCrafter; registers itself)
