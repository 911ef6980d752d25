"""The scenarios of the benchmark, by config name."""

from __future__ import annotations

from pillagerbench.config.registry import Registry
from pillagerbench.scenarios.base import GameMaster, PlayerSpec, Scenario, Side
from pillagerbench.scenarios.dash_and_dine import DashAndDine
from pillagerbench.scenarios.layout import PAPER, LayoutKey
from pillagerbench.scenarios.mushroom_war import MushroomWar

SCENARIOS: Registry[type[Scenario]] = Registry("scenario", {cls.key: cls for cls in (MushroomWar, DashAndDine)})


def make_scenario(name: str, layout: LayoutKey = PAPER, **options) -> Scenario:
    """A scenario by config name, on a layout ("paper", a seed, or a layout file; docs/layouts.md)."""
    scenario = SCENARIOS.find(name)(**options)
    return scenario if layout == PAPER else scenario.with_layout(layout)


__all__ = ["SCENARIOS", "GameMaster", "PlayerSpec", "Scenario", "Side", "make_scenario"]
