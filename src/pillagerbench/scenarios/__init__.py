"""The scenarios of the benchmark, by config name."""

from __future__ import annotations

from pillagerbench.config import ConfigError
from pillagerbench.scenarios.base import GameMaster, PlayerSpec, Scenario, Side
from pillagerbench.scenarios.dash_and_dine import DashAndDine
from pillagerbench.scenarios.mushroom_war import MushroomWar

SCENARIOS: dict[str, type[Scenario]] = {cls.key: cls for cls in (MushroomWar, DashAndDine)}


def make_scenario(name: str, **options) -> Scenario:
    if name not in SCENARIOS:
        raise ConfigError(f"unknown scenario {name!r}; valid scenarios: {', '.join(SCENARIOS)}")
    return SCENARIOS[name](**options)


__all__ = ["SCENARIOS", "GameMaster", "PlayerSpec", "Scenario", "Side", "make_scenario"]
