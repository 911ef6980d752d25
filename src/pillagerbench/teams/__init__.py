"""Teams (multi-agent systems): the registry (`registry.py`: names, entry points, import paths)
with the built-in teams."""

from __future__ import annotations

from pillagerbench.teams.base import Team, TeamContext
from pillagerbench.teams.cot import ChainOfThought
from pillagerbench.teams.dash_and_dine import Berries, CakeBeetroot, MelonPumpkin, PotatoCookie
from pillagerbench.teams.do_nothing import DoNothing
from pillagerbench.teams.human import Human
from pillagerbench.teams.mushroom_war import Aggressive, Balanced, Passive, Slimy
from pillagerbench.teams.random_team import RandomTeam
from pillagerbench.teams.registry import (
    TEAMS,
    available,
    declared_options,
    find_team,
    make_team,
    register,
    team_from_config,
)
from pillagerbench.teams.remote import RemoteTeam
from pillagerbench.teams.tacticrafter import TactiCrafter
from pillagerbench.teams.tools import AgentTeam, ToolsTeam

BUILT_IN: tuple[type[Team], ...] = (
    DoNothing,
    Aggressive,
    Balanced,
    Passive,
    Slimy,
    Berries,
    CakeBeetroot,
    MelonPumpkin,
    PotatoCookie,  # scripted
    ChainOfThought,
    RandomTeam,  # the paper's baselines
    TactiCrafter,  # the paper's own system
    RemoteTeam,  # a team in any language behind HTTP (docs/remote-teams.md)
    AgentTeam,  # a team an outside agent plays through the game's tools (docs/any-agent.md)
    ToolsTeam,  # an LLM team playing through the same tools by function calling (beyond the paper)
    Human,  # people playing from the browser (docs/people.md)
)
for _cls in BUILT_IN:
    register(_cls)

__all__ = [
    "BUILT_IN",
    "TEAMS",
    "Team",
    "TeamContext",
    "available",
    "declared_options",
    "find_team",
    "make_team",
    "register",
    "team_from_config",
]
