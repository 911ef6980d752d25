"""The scenarios of the benchmark, by config name."""

from __future__ import annotations

from pillagerbench.config import ConfigError
from pillagerbench.scenarios.base import GameMaster, PlayerSpec, Scenario, Side
from pillagerbench.scenarios.dash_and_dine import DashAndDine
from pillagerbench.scenarios.layout import PAPER, LayoutKey
from pillagerbench.scenarios.mushroom_war import MushroomWar

SCENARIOS: dict[str, type[Scenario]] = {cls.key: cls for cls in (MushroomWar, DashAndDine)}


def make_scenario(name: str, layout: LayoutKey = PAPER, **options) -> Scenario:
    """A scenario by config name, on a layout ("paper", a seed, or a layout file; docs/layouts.md)."""
    if name not in SCENARIOS:
        raise ConfigError(f"unknown scenario {name!r}; valid scenarios: {', '.join(SCENARIOS)}")
    scenario = SCENARIOS[name](**options)
    return scenario if layout == PAPER else scenario.with_layout(layout)


__all__ = ["SCENARIOS", "GameMaster", "PlayerSpec", "Scenario", "Side", "make_scenario"]
