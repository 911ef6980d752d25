"""Teams (multi-agent systems) by config name: the registry (`registry.py`) with the built-in teams."""

from __future__ import annotations

from pillagerbench.teams.base import Team, TeamContext
from pillagerbench.teams.cot import ChainOfThought
from pillagerbench.teams.dash_and_dine import Berries, CakeBeetroot, MelonPumpkin, PotatoCookie
from pillagerbench.teams.do_nothing import DoNothing
from pillagerbench.teams.mushroom_war import Aggressive, Balanced, Passive, Slimy
from pillagerbench.teams.random_team import RandomTeam
from pillagerbench.teams.registry import TEAMS, make_team, register, team_from_config, team_options
from pillagerbench.teams.tacticrafter import TactiCrafter

BUILT_IN: tuple[type[Team], ...] = (
    DoNothing, Aggressive, Balanced, Passive, Slimy, Berries, CakeBeetroot, MelonPumpkin, PotatoCookie,  # scripted
    ChainOfThought, RandomTeam,  # the paper's baselines
    TactiCrafter,  # the paper's own system
)
for _cls in BUILT_IN:
    register(_cls)

__all__ = ["BUILT_IN", "TEAMS", "Team", "TeamContext", "make_team", "register", "team_from_config", "team_options"]
