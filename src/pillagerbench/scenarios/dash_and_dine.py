"""Dash & Dine: teams farm, cook and craft food and give it to their team's server, a player that
receives it. Only the first three food types a server receives count for its team (locked in by
whoever gives them first, opponents included); the farms are shared.

Where the farms, chests, furnaces and bases are is the layout's (dash_and_dine_layout.py: the map
inferred from upstream's coordinates for `layout=paper`, or a generated variant).
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass
from typing import ClassVar

from pillagerbench.config.sides import SIDES
from pillagerbench.scenarios import dash_and_dine_layout as L
from pillagerbench.scenarios.arena import GROUND_Y, Arena, standing
from pillagerbench.scenarios.base import GameMaster, PlayerSpec, Scenario, Side, sides_at, vec
from pillagerbench.scenarios.layout import LayoutRules

Y = GROUND_Y + 1
LOCK_IN_TYPES = 3
SERVER_PERIOD_S = 2.0

# Points per food item (hunger + saturation restored, as upstream). Raw beef and chicken use their
# real item ids and score as the description says (upstream's keys never matched).
REWARDS = {
    "apple": 6.4,
    "baked_potato": 11,
    "beetroot": 2.2,
    "beetroot_soup": 13.2,
    "bread": 11,
    "cake": 16.8,
    "carrot": 6.6,
    "chorus_fruit": 6.4,
    "cooked_beef": 20.8,
    "cooked_chicken": 13.2,
    "cooked_cod": 11,
    "cooked_mutton": 15.6,
    "cooked_porkchop": 20.8,
    "cooked_rabbit": 11,
    "cooked_salmon": 15.6,
    "cookie": 2.4,
    "dried_kelp": 1.6,
    "enchanted_golden_apple": 13.6,
    "golden_apple": 13.6,
    "golden_carrot": 20.4,
    "honey_bottle": 7.2,
    "melon_slice": 3.2,
    "mushroom_stew": 13.2,
    "poisonous_potato": 3.2,
    "potato": 1.6,
    "pufferfish": 1.2,
    "pumpkin_pie": 12.8,
    "rabbit_stew": 22,
    "beef": 4.8,
    "chicken": 3.2,
    "cod": 2.4,
    "mutton": 3.2,
    "porkchop": 4.8,
    "rabbit": 4.8,
    "salmon": 2.4,
    "rotten_flesh": 4.8,
    "spider_eye": 5.2,
    "suspicious_stew": 13.2,
    "sweet_berries": 2.4,
    "tropical_fish": 1.2,
}

# The food list shown to LLMs (reference §4.2): item, how to get it.
FOODS = [
    ("baked_potato", "smelt a potato in a furnace"),
    ("beef", "dropped by a cow"),
    ("beetroot", "farmed"),
    ("beetroot_soup", "craft 6 beetroot + 1 bowl"),
    ("bread", "craft 3 wheat"),
    ("cake", "craft 3 milk_bucket + 2 sugar + 3 wheat + 1 egg"),
    ("carrot", "farmed"),
    ("chicken", "dropped by a chicken"),
    ("cooked_beef", "smelt beef"),
    ("cooked_chicken", "smelt chicken"),
    ("cookie", "craft 2 wheat + 1 cocoa_beans"),
    ("golden_carrot", "craft 8 gold_nugget + 1 carrot"),
    ("melon_slice", "farmed"),
    ("poisonous_potato", "sometimes comes with harvested potatoes"),
    ("potato", "farmed"),
    ("pumpkin_pie", "craft 1 pumpkin + 1 sugar + 1 egg"),
    ("sugar", "craft 1 sugar_cane"),
    ("sugar_cane", "farmed"),
    ("sweet_berries", "farmed"),
]

SERVER_NAMES = {"red": "Red_Server", "blue": "Blue_Server"}
LAYOUTS = LayoutRules("dash_and_dine", L.DashAndDineLayout, L.PAPER_LAYOUT, L.generate, L.problems)


def build_arena(layout: L.DashAndDineLayout) -> Arena:
    """Every station of the layout, in the order of `STATIONS`."""
    arena = Arena(box=L.BOX)
    for piece in layout.pieces().values():
        arena.blocks += piece.blocks
        arena.chests.update(piece.chests)
        arena.furnaces.update(piece.furnaces)
        arena.mobs = [*arena.mobs, *piece.mobs]
        arena.egg_farms += piece.egg_farms
    return arena


@dataclass
class DashAndDine(Scenario[L.DashAndDineLayout]):
    key = "dash_and_dine"
    title = "Dash and Dine"
    primitives = (
        "mineBlock",
        "craftItem",
        "placeItem",
        "multiAgent",
        "farm",
        "smeltItem",
        "killMob",
        "giveToPlayer",
        "useChest",
    )
    random_tick_speed: ClassVar[int] = 200
    layouts: ClassVar[LayoutRules[L.DashAndDineLayout]] = LAYOUTS

    @property
    def servers(self) -> dict[str, PlayerSpec]:
        """Each side's server: a player of the scenario's that receives the food (creative: unkillable)."""
        return {
            k: PlayerSpec(n, standing(self.layout.base(k).server), gamemode="creative") for k, n in SERVER_NAMES.items()
        }

    @property
    def sides(self) -> tuple[Side, ...]:
        bases = {key: self.layout.base(key) for key in SIDES}
        return sides_at(
            {k: [standing(p) for p in b.players] for k, b in bases.items()},
            {k: standing(b.server) for k, b in bases.items()},
        )

    @property
    def extra_players(self) -> tuple[PlayerSpec, ...]:
        return tuple(self.servers.values())

    @property
    def arena(self) -> Arena:
        return build_arena(self.layout)

    def placeholders(self, key: str) -> dict:
        out = super().placeholders(key)
        out.update(server_name=SERVER_NAMES[key], ground_y=GROUND_Y, **{k: vec(self.layout.poi(k)) for k in L.STATIONS})
        return out

    def description(self) -> str:
        r, b = self.sides
        servers = self.servers
        lines = [
            f"Dash and Dine: two teams of two compete. The red team is {' and '.join(r.player_names)}; "
            f"the blue team is {' and '.join(b.player_names)}.",
            "Your team earns points by making food and giving it to your team's server, which is a player.",
            f"A server takes only {LOCK_IN_TYPES} different food types, but any amount of each of them.",
            f"The red team's server is {servers['red'].name} at ({vec(servers['red'].spawn)}); the blue team's is "
            f"{servers['blue'].name} at ({vec(servers['blue'].spawn)}).",
            f"The ground is flat; its top layer is at y = {GROUND_Y}, so players stand at y = {Y}.",
            "A food is worth the hunger and saturation it restores (table below).",
            "Both teams share the farms. The random tick speed is "
            f"{self.random_tick_speed}, so crops grow back very quickly.",
            "The game lasts an unknown amount of time: aim for the most points in the long run. "
            "The team with the most points wins. Sabotage is allowed.",
            "Points of interest:",
            *[f"- {station.text}: ({vec(self.layout.poi(k))})" for k, station in L.STATIONS.items()],
            "Food (how to get it: points):",
            *[f"- {item}: {how}: {REWARDS.get(item, 0):g}" for item, how in FOODS],
        ]
        return "\n".join(lines)

    def game_master(self, server, rng: random.Random) -> DashAndDineMaster:
        return DashAndDineMaster(self, server, rng)


class DashAndDineMaster(GameMaster):
    period_s = SERVER_PERIOD_S
    scenario: DashAndDine

    async def start(self) -> None:
        self.servers = self.scenario.servers
        self.locked: dict[str, list[str]] = {key: [] for key in self.servers}
        self.points: dict[str, float] = {key: 0.0 for key in self.servers}
        self.rounded: dict[str, float] = {key: 0.0 for key in self.servers}  # upstream's sum of rounded scans
        await self.say("starting dining scenario...")  # as upstream's servers

    async def step(self) -> None:
        for key, server_player in self.servers.items():
            try:
                inventory = await self.server.inventory(server_player.name)
            except Exception as exc:  # noqa: BLE001 - logged; the other server is still emptied
                self.log.append({"error": f"{server_player.name}: {exc}"})
                continue
            if not inventory:
                continue
            await self.server.clear(server_player.name)
            gained = 0.0
            for slot in inventory:
                item = slot["name"]
                if item not in REWARDS:
                    continue
                locked = self.locked[key]
                if item not in locked and len(locked) < LOCK_IN_TYPES:
                    locked.append(item)
                    await self.say(f"Locked-in {item} as a submission item for team_{key}")
                if item in locked:
                    gained += slot["count"] * REWARDS[item]
            if gained > 0:
                self.points[key] += gained
                self.rounded[key] += upstream_round(gained)
                await self.say(f"Scored {gained:g} points for team_{key}")

    async def scores(self) -> dict[str, float]:
        return {key: round(v, 4) for key, v in self.points.items()}

    async def upstream_scores(self, runs: dict[str, int]) -> dict[str, float]:
        """Upstream's quirk: each scan's points were rounded before they were added."""
        return dict(self.rounded)


def upstream_round(x: float) -> float:
    """JavaScript's Math.round (halves up), as upstream's server loop rounded each scan."""
    return float(math.floor(x + 0.5))
