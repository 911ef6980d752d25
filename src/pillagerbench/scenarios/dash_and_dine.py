"""Dash & Dine: teams farm, cook and craft food and give it to their team's server, a player that
receives it. Only the first three food types a server receives count for its team (locked in by
whoever gives them first, opponents included); the farms are shared.

The farm builds are inferred from upstream's coordinates and scenario text (its region files are
lost): rows of ripe crops at the stated positions, y + 64.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass
from typing import ClassVar

from pillagerbench.scenarios.arena import GROUND_Y, Arena
from pillagerbench.scenarios.base import GameMaster, PlayerSpec, Scenario, Side, vec

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

SERVERS = {
    "red": PlayerSpec("Red_Server", (-1, Y, -9), gamemode="creative"),
    "blue": PlayerSpec("Blue_Server", (-1, Y, 7), gamemode="creative"),
}
PLAYERS = {"red": [("Ryn", (-5, Y, -10)), ("Raze", (-5, Y, -8))], "blue": [("Byte", (-5, Y, 6)), ("Blink", (-5, Y, 8))]}

# Points of interest: (description, reference position, builder). Builders add to an Arena.
FURNACES = [(2, Y + 1, -2), (2, Y + 1, -1), (2, Y + 1, 0)]
BOWL_CHEST = (-3, Y + 1, -1)
BUCKET_CHEST = (-7, Y, -7)
EGG_CHEST = (-7, Y, 5)
TOOL_CHEST = (-11, Y + 1, -1)


def rect(x0: int, x1: int, z0: int, z1: int) -> list[tuple[int, int]]:
    return [(x, z) for x in range(x0, x1 + 1) for z in range(z0, z1 + 1)]


# Farmland of the built farms is moist (moisture 7), as beside water; our farmland does not dry out.
MOIST = {"moisture": 7}


def crop_field(cells, crop, age):
    return [(x, GROUND_Y, z, "farmland", MOIST) for x, z in cells] + [(x, Y, z, crop, {"age": age}) for x, z in cells]


# Farm sizes and shapes are not in the reference (its region files are lost); each is the smallest
# shape that fits the farm's stated width and gives the farm's stated yield per minute under vanilla
# growth at randomTickSpeed 200 (docs/fidelity.md, "World and rules against the reference").
SUGAR_CANE = rect(-12, -10, -8, -8)  # 3 columns: 11.0 cane/min (stated ~11)
BERRIES = rect(-12, -10, 5, 7)  # 9 bushes: 158 berries/min (stated ~160)
COCOA_LOGS = [(x, y, z) for x in range(-16, -13) for z in (-9, -8) for y in (Y, Y + 1)]  # 12 jungle logs
COCOA_PODS = [(x, Y, -7) for x in range(-16, -13)]  # 3 ripe pods: 52.7 beans/min (stated ~54)
# Melon and pumpkin stems: 2 and 4, as many seeds as the world's builder used (upstream's stats file:
# melon_seeds 2, pumpkin_seeds 4), no two side by side, so each can grow its fruit on all four sides;
# each has grown one already, on the side it faces: (stem x, z, facing). 107 fruit/min (stated ~125).
MELON_STEMS = [(-16, -2, "west"), (-16, 0, "west")]
PUMPKIN_STEMS = [(-14, -2, "east"), (-14, 0, "east"), (-15, -3, "north"), (-15, 1, "south")]
SIDES = {"east": (1, 0), "west": (-1, 0), "south": (0, 1), "north": (0, -1)}  # facing: (dx, dz)
BEETROOTS = rect(-16, -14, 5, 7)  # 3 x 3: 15.4 beetroot/min (stated ~13)
CARROTS = rect(-20, -18, -9, -7)  # 3 x 3: 36.8 carrots/min (stated ~35)
WHEAT = rect(-20, -18, -3, 1)  # 3 x 5: 17.5 wheat/min (stated ~17)
POTATOES = rect(-20, -18, 5, 7)  # 3 x 3: 36.8 potatoes/min (stated ~35)
CHICKENS = 14  # the saved world's entity file; vanilla laying (300-600 s each) gives 1.9 eggs/min (stated ~2)
EGG_LAY_S = 300.0


def build_arena() -> Arena:
    blocks: list[tuple] = []
    for p in FURNACES:
        blocks += [(p[0], Y, p[2], "stone_bricks"), (*p, "furnace")]
    blocks += [(BOWL_CHEST[0], Y, BOWL_CHEST[2], "stone_bricks"), (*BOWL_CHEST, "chest")]
    blocks += [(*BUCKET_CHEST, "chest"), (*EGG_CHEST, "chest")]
    # egg farm: chickens in a glass pen next to the egg chest
    blocks += [(x, y, z, "glass") for x, z in [(-8, 6), (-6, 6), (-7, 7), (-8, 7), (-6, 7)] for y in (Y, Y + 1)]
    blocks += [
        (TOOL_CHEST[0], Y, TOOL_CHEST[2], "stone_bricks"),
        (*TOOL_CHEST, "chest"),
        (-12, Y, -1, "crafting_table"),
        (-10, Y, -1, "crafting_table"),
    ]
    # sugar cane: 3 high, on sand beside water
    for x, z in SUGAR_CANE:
        blocks += [(x, GROUND_Y, z, "sand"), (x, GROUND_Y, z - 1, "water")]
        blocks += [(x, y, z, "sugar_cane") for y in range(Y, Y + 3)]
    # sweet berry bushes, ripe, on dirt
    blocks += [(x, GROUND_Y, z, "dirt") for x, z in BERRIES] + [
        (x, Y, z, "sweet_berry_bush", {"age": 3}) for x, z in BERRIES
    ]
    # cocoa: jungle logs 2 high with ripe pods on their south side
    blocks += [(*p, "jungle_log") for p in COCOA_LOGS]
    blocks += [(*p, "cocoa", {"age": 2, "facing": "north"}) for p in COCOA_PODS]
    # melons and pumpkins: moist farmland 5 x 5, each stem with its grown fruit
    blocks += [(x, GROUND_Y, z, "farmland", MOIST) for x, z in rect(-17, -13, -3, 1)]
    for stems, fruit in ((MELON_STEMS, "melon"), (PUMPKIN_STEMS, "pumpkin")):
        for x, z, facing in stems:
            dx, dz = SIDES[facing]
            blocks += [(x, Y, z, f"attached_{fruit}_stem", {"facing": facing}), (x + dx, Y, z + dz, fruit)]
    blocks += crop_field(BEETROOTS, "beetroots", 3)
    blocks += crop_field(CARROTS, "carrots", 7)
    blocks += crop_field(WHEAT, "wheat", 7)
    blocks += crop_field(POTATOES, "potatoes", 7)
    return Arena(
        box=((-26, 1, -16), (6, Y + 8, 14)),
        blocks=blocks,
        chests={
            BOWL_CHEST: {"bowl": 64},
            BUCKET_CHEST: {"bucket": 16},
            EGG_CHEST: {},  # only what the chickens lay during the game
            TOOL_CHEST: {"gold_nugget": 64, "netherite_hoe": 1},
        },
        furnaces={p: {"fuel": ["coal", 64]} for p in FURNACES},
        mobs=[("cow", (-6.5, Y, -8.5))] + [("chicken", (-6.5, Y, 6.5))] * CHICKENS,
        egg_farms=[(EGG_CHEST, EGG_LAY_S)],
    )


# Points of interest: placeholder name for scripts, text for LLMs (with the yields upstream's
# description stated), reference position.
POINTS_OF_INTEREST = [
    ("furnace", "3 furnaces, each loaded with 64 coal", FURNACES[1]),
    ("bowl_chest", "chest with 64 bowls", BOWL_CHEST),
    ("bucket_chest", "chest with 16 buckets, and one cow next to it", BUCKET_CHEST),
    (
        "egg_chest",
        f"chest that an egg farm of {CHICKENS} chickens fills with eggs (about 2 eggs per minute)",
        EGG_CHEST,
    ),
    ("tool_chest", "2 crafting tables and a chest with 64 gold nuggets and a netherite hoe", TOOL_CHEST),
    ("sugar_cane_farm", "3-wide sugar cane farm (about 11 sugar cane per minute)", (-11, Y, -8)),
    ("berry_farm", "3-wide sweet berry farm (about 160 sweet berries per minute)", (-11, Y, 6)),
    ("cocoa_farm", "2-high cocoa bean farm (about 54 cocoa beans per minute)", (-15, Y, -8)),
    ("melon_pumpkin_farm", "5-wide melon and pumpkin farm (about 125 melons and pumpkins per minute)", (-15, Y, -1)),
    ("beetroot_farm", "3-wide beetroot farm (about 13 beetroots per minute)", (-15, Y, 6)),
    ("carrot_farm", "3-wide carrot farm (about 35 carrots per minute)", (-19, Y, -8)),
    ("wheat_farm", "5-wide wheat farm (about 17 wheat per minute)", (-19, Y, -1)),
    ("potato_farm", "3-wide potato farm (about 35 potatoes per minute)", (-19, Y, 6)),
]


@dataclass
class DashAndDine(Scenario):
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

    @property
    def sides(self) -> tuple[Side, ...]:
        return tuple(
            Side(key, f"{key}_team", key, tuple(PlayerSpec(n, p) for n, p in PLAYERS[key]), SERVERS[key].spawn)
            for key in ("red", "blue")
        )

    @property
    def extra_players(self) -> tuple[PlayerSpec, ...]:
        return tuple(SERVERS.values())

    @property
    def arena(self) -> Arena:
        return build_arena()

    def placeholders(self, key: str) -> dict:
        out = super().placeholders(key)
        out.update(
            server_name=SERVERS[key].name, ground_y=GROUND_Y, **{key: vec(p) for key, _, p in POINTS_OF_INTEREST}
        )
        return out

    def description(self) -> str:
        r, b = self.sides
        lines = [
            f"Dash and Dine: two teams of two compete. The red team is {' and '.join(r.player_names)}; "
            f"the blue team is {' and '.join(b.player_names)}.",
            "Your team earns points by making food and giving it to your team's server, which is a player.",
            f"A server takes only {LOCK_IN_TYPES} different food types, but any amount of each of them.",
            f"The red team's server is {SERVERS['red'].name} at ({vec(SERVERS['red'].spawn)}); the blue team's is "
            f"{SERVERS['blue'].name} at ({vec(SERVERS['blue'].spawn)}).",
            f"The ground is flat; its top layer is at y = {GROUND_Y}, so players stand at y = {Y}.",
            "A food is worth the hunger and saturation it restores (table below).",
            "Both teams share the farms. The random tick speed is "
            f"{self.random_tick_speed}, so crops grow back very quickly.",
            "The game lasts an unknown amount of time: aim for the most points in the long run. "
            "The team with the most points wins. Sabotage is allowed.",
            "Points of interest:",
            *[f"- {text}: ({vec(p)})" for _, text, p in POINTS_OF_INTEREST],
            "Food (how to get it: points):",
            *[f"- {item}: {how}: {REWARDS.get(item, 0):g}" for item, how in FOODS],
        ]
        return "\n".join(lines)

    def game_master(self, server, rng: random.Random) -> DashAndDineMaster:
        return DashAndDineMaster(self, server, rng)


class DashAndDineMaster(GameMaster):
    period_s = SERVER_PERIOD_S

    async def start(self) -> None:
        self.locked: dict[str, list[str]] = {key: [] for key in SERVERS}
        self.points: dict[str, float] = {key: 0.0 for key in SERVERS}
        self.rounded: dict[str, float] = {key: 0.0 for key in SERVERS}  # upstream's sum of rounded scans
        await self.say("starting dining scenario...")  # as upstream's servers

    async def step(self) -> None:
        for key, server_player in SERVERS.items():
            try:
                inventory = await self.server.request("inventory", player=server_player.name)
            except Exception as exc:  # noqa: BLE001 - logged; the other server is still emptied
                self.log.append({"error": f"{server_player.name}: {exc}"})
                continue
            if not inventory:
                continue
            await self.server.request("clear", player=server_player.name)
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
