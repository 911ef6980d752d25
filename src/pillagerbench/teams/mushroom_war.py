"""Mushroom War's built-in opponents (reference §6), as loops over shared behaviours."""

from pillagerbench.teams.scripted import ScriptedTeam

CLEAN = "cleanOwn(8)"
POLLUTE = "pollute(8)"
HARVEST_OR_CLEAN = "harvest(true)"
HARVEST = "harvest(false)"
SABOTAGE = "sabotage()"


class MushroomWarTeam(ScriptedTeam):
    scenarios = ("mushroom_war",)


class Aggressive(MushroomWarTeam):
    name = "aggressive"
    parts = ((CLEAN, POLLUTE), (HARVEST_OR_CLEAN, SABOTAGE))


class Balanced(MushroomWarTeam):
    name = "balanced"
    parts = ((CLEAN, HARVEST), (SABOTAGE,))


class Passive(MushroomWarTeam):
    name = "passive"
    parts = ((HARVEST_OR_CLEAN,), (CLEAN,))


class Slimy(MushroomWarTeam):
    name = "slimy"
    parts = ((HARVEST_OR_CLEAN,), (CLEAN, POLLUTE))
