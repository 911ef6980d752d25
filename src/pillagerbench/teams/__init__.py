"""Teams (multi-agent systems) by config name, entry point or import path (registry.py)."""

from __future__ import annotations

from pillagerbench.teams.base import Team, TeamContext
from pillagerbench.teams.dash_and_dine import Berries, CakeBeetroot, MelonPumpkin, PotatoCookie
from pillagerbench.teams.do_nothing import DoNothing
from pillagerbench.teams.mushroom_war import Aggressive, Balanced, Passive, Slimy
from pillagerbench.teams.registry import TEAMS, available, declared_options, find_team, make_team, register

for _cls in (DoNothing, Aggressive, Balanced, Passive, Slimy, Berries, CakeBeetroot, MelonPumpkin, PotatoCookie):
    register(_cls)

__all__ = ["TEAMS", "Team", "TeamContext", "available", "declared_options", "find_team", "make_team", "register"]

from pillagerbench.teams import cot, random_team  # noqa: E402,F401  (baselines; they register themselves)
from pillagerbench.teams import tacticrafter  # noqa: E402,F401  (the paper's TactiCrafter; registers itself)
from pillagerbench.teams.remote import team as _remote  # noqa: E402,F401  (remote teams; registers itself)
