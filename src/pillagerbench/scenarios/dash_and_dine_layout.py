"""Dash & Dine's layouts: where each station (a farm, the furnaces, a chest with what stands beside
it) and each side's base (its server player and its two players' spawns) are. A station's shape,
crop and contents are its kind's (`STATIONS`); a layout places every kind once, by an anchor cell.

`PAPER` is the map inferred from upstream's coordinates (y + 64); `generate(seed)` builds a
variant by the rules of docs/layouts.md; `problems(layout)` checks any layout against those rules.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict

from pillagerbench.config.sides import SIDES
from pillagerbench.scenarios.arena import GROUND_Y
from pillagerbench.scenarios.layout import PAPER, Cell, Draw, LayoutKey, apart, search, unreachable

Y = GROUND_Y + 1
BOX = ((-26, 1, -16), (6, Y + 8, 14))
MIDDLE_Z = -1  # the line between the two bases
MOIST = {"moisture": 7}  # built farmland is moist, as beside water; ours does not dry out
CHICKENS = 14  # the saved world's entity file; vanilla laying (300-600 s each) gives 1.9 eggs/min (stated ~2)
EGG_LAY_S = 300.0
# the seeds the world's builder used (upstream's stats file: melon_seeds 2, pumpkin_seeds 4), each
# stem with the fruit it grew on the side it faces: (dx, dz, facing) from the farm's anchor
MELON_STEMS = [(-1, -1, "west"), (-1, 1, "west")]
PUMPKIN_STEMS = [(1, -1, "east"), (1, 1, "east"), (0, -2, "north"), (0, 2, "south")]
FACING = {"east": (1, 0), "west": (-1, 0), "south": (0, 1), "north": (0, -1)}
PASSABLE = {"wheat", "carrots", "potatoes", "beetroots", "sweet_berry_bush", "sugar_cane"}


@dataclass
class Piece:
    """What one station adds to the arena (arena.Arena's fields)."""

    blocks: list[tuple] = field(default_factory=list)
    chests: dict[tuple, dict[str, int]] = field(default_factory=dict)
    furnaces: dict[tuple, dict[str, Any]] = field(default_factory=dict)
    mobs: list[tuple[str, tuple[float, float, float]]] = field(default_factory=list)
    egg_farms: list[tuple[tuple, float]] = field(default_factory=list)

    def cells(self) -> set[Cell]:
        """The cells the station occupies (its blocks and its mobs' spots)."""
        return {(b[0], b[2]) for b in self.blocks} | {(math.floor(p[0]), math.floor(p[2])) for _, p in self.mobs}

    def blocked(self) -> set[Cell]:
        """The cells no one walks through: a solid block at the feet or head, or water in the ground."""
        return {
            (b[0], b[2])
            for b in self.blocks
            if (b[1] in (Y, Y + 1) and b[3] not in PASSABLE) or (b[1] == GROUND_Y and b[3] == "water")
        }

    def targets(self) -> list[Cell]:
        """The cells of blocks a player works (not glass, stone bricks or the ground under a crop)."""
        return sorted({(b[0], b[2]) for b in self.blocks if b[1] >= Y and b[3] not in ("glass", "stone_bricks")})


def rect(x0: int, x1: int, z0: int, z1: int) -> list[Cell]:
    return [(x, z) for x in range(x0, x1 + 1) for z in range(z0, z1 + 1)]


def _crops(crop: str, age: int, dx: tuple[int, int], dz: tuple[int, int]) -> Callable[[int, int], Piece]:
    def build(x: int, z: int) -> Piece:
        cells = rect(x + dx[0], x + dx[1], z + dz[0], z + dz[1])
        return Piece(
            [(a, GROUND_Y, b, "farmland", MOIST) for a, b in cells] + [(a, Y, b, crop, {"age": age}) for a, b in cells]
        )

    return build


def _sugar_cane(x: int, z: int) -> Piece:  # 3 high, on sand beside water (north of it)
    blocks: list[tuple] = []
    for a in range(x - 1, x + 2):
        blocks += [(a, GROUND_Y, z, "sand"), (a, GROUND_Y, z - 1, "water")] + [
            (a, y, z, "sugar_cane") for y in range(Y, Y + 3)
        ]
    return Piece(blocks)


def _berries(x: int, z: int) -> Piece:  # ripe bushes on dirt
    cells = rect(x - 1, x + 1, z - 1, z + 1)
    return Piece(
        [(a, GROUND_Y, b, "dirt") for a, b in cells] + [(a, Y, b, "sweet_berry_bush", {"age": 3}) for a, b in cells]
    )


def _cocoa(x: int, z: int) -> Piece:  # jungle logs 2 high, ripe pods on the logs' south side
    logs = [(a, y, b, "jungle_log") for a in range(x - 1, x + 2) for b in (z - 1, z) for y in (Y, Y + 1)]
    return Piece(logs + [(a, Y, z + 1, "cocoa", {"age": 2, "facing": "north"}) for a in range(x - 1, x + 2)])


def _melons_pumpkins(x: int, z: int) -> Piece:  # moist farmland 5 x 5, each stem with its grown fruit
    blocks: list[tuple] = [(a, GROUND_Y, b, "farmland", MOIST) for a, b in rect(x - 2, x + 2, z - 2, z + 2)]
    for stems, fruit in ((MELON_STEMS, "melon"), (PUMPKIN_STEMS, "pumpkin")):
        for dx, dz, facing in stems:
            fx, fz = FACING[facing]
            blocks += [
                (x + dx, Y, z + dz, f"attached_{fruit}_stem", {"facing": facing}),
                (x + dx + fx, Y, z + dz + fz, fruit),
            ]
    return Piece(blocks)


def _furnaces(x: int, z: int) -> Piece:  # 3 furnaces on stone bricks, each loaded with 64 coal
    spots = [(x, Y + 1, b) for b in (z - 1, z, z + 1)]
    blocks = [b for p in spots for b in ((p[0], Y, p[2], "stone_bricks"), (*p, "furnace"))]
    return Piece(blocks, furnaces={p: {"fuel": ["coal", 64]} for p in spots})


def _raised_chest(items: dict[str, int], tables: bool = False) -> Callable[[int, int], Piece]:
    def build(x: int, z: int) -> Piece:
        blocks: list[tuple] = [(x, Y, z, "stone_bricks"), (x, Y + 1, z, "chest")]
        if tables:
            blocks += [(x - 1, Y, z, "crafting_table"), (x + 1, Y, z, "crafting_table")]
        return Piece(blocks, chests={(x, Y + 1, z): dict(items)})

    return build


def _bucket_chest(x: int, z: int) -> Piece:  # a chest with buckets, one cow beside it
    return Piece([(x, Y, z, "chest")], chests={(x, Y, z): {"bucket": 16}}, mobs=[("cow", (x + 0.5, Y, z - 1.5))])


def _egg_chest(x: int, z: int) -> Piece:  # the chickens in a glass pen behind the chest fill it with eggs
    pen = [
        (a, y, b, "glass")
        for a, b in [(x - 1, z + 1), (x + 1, z + 1), (x, z + 2), (x - 1, z + 2), (x + 1, z + 2)]
        for y in (Y, Y + 1)
    ]
    return Piece(
        [(x, Y, z, "chest"), *pen],
        chests={(x, Y, z): {}},  # only what the chickens lay during the game
        mobs=[("chicken", (x + 0.5, Y, z + 1.5))] * CHICKENS,
        egg_farms=[((x, Y, z), EGG_LAY_S)],
    )


@dataclass(frozen=True)
class Station:
    text: str  # what the LLM description says of it (with the yields upstream's description stated)
    build: Callable[[int, int], Piece]
    poi_dy: int = 0  # the point of interest: the anchor cell, this many blocks above the standing layer


# Farm sizes and shapes are not in the reference (its region files are lost); each is the smallest
# shape that fits the farm's stated width and gives the farm's stated yield per minute under vanilla
# growth at randomTickSpeed 200 (docs/fidelity.md, "World and rules against the reference").
# Order: the description's. Keys: the built-in opponents' script placeholders.
STATIONS: dict[str, Station] = {
    "furnace": Station("3 furnaces, each loaded with 64 coal", _furnaces, 1),
    "bowl_chest": Station("chest with 64 bowls", _raised_chest({"bowl": 64}), 1),
    "bucket_chest": Station("chest with 16 buckets, and one cow next to it", _bucket_chest),
    "egg_chest": Station(
        f"chest that an egg farm of {CHICKENS} chickens fills with eggs (about 2 eggs per minute)", _egg_chest
    ),
    "tool_chest": Station(
        "2 crafting tables and a chest with 64 gold nuggets and a netherite hoe",
        _raised_chest({"gold_nugget": 64, "netherite_hoe": 1}, tables=True),
        1,
    ),
    "sugar_cane_farm": Station("3-wide sugar cane farm (about 11 sugar cane per minute)", _sugar_cane),
    "berry_farm": Station("3-wide sweet berry farm (about 160 sweet berries per minute)", _berries),
    "cocoa_farm": Station("2-high cocoa bean farm (about 54 cocoa beans per minute)", _cocoa),
    "melon_pumpkin_farm": Station(
        "5-wide melon and pumpkin farm (about 125 melons and pumpkins per minute)", _melons_pumpkins
    ),
    "beetroot_farm": Station(
        "3-wide beetroot farm (about 13 beetroots per minute)", _crops("beetroots", 3, (-1, 1), (-1, 1))
    ),
    "carrot_farm": Station("3-wide carrot farm (about 35 carrots per minute)", _crops("carrots", 7, (-1, 1), (-1, 1))),
    "wheat_farm": Station("5-wide wheat farm (about 17 wheat per minute)", _crops("wheat", 7, (-1, 1), (-2, 2))),
    "potato_farm": Station(
        "3-wide potato farm (about 35 potatoes per minute)", _crops("potatoes", 7, (-1, 1), (-1, 1))
    ),
}


class _Frozen(BaseModel):
    model_config = ConfigDict(frozen=True, extra="forbid")


class Base(_Frozen):
    server: Cell  # the side's server player (x, z)
    players: tuple[Cell, Cell]  # the side's players' spawns, in its player order


class DashAndDineLayout(_Frozen):
    scenario: Literal["dash_and_dine"] = "dash_and_dine"
    key: LayoutKey = PAPER
    red: Base
    blue: Base
    stations: dict[str, Cell]  # station kind -> anchor (x, z)

    def base(self, side: str) -> Base:
        return self.red if side == "red" else self.blue

    def pieces(self) -> dict[str, Piece]:
        return {kind: STATIONS[kind].build(*self.stations[kind]) for kind in STATIONS if kind in self.stations}

    def poi(self, kind: str) -> tuple[int, int, int]:
        x, z = self.stations[kind]
        return (x, Y + STATIONS[kind].poi_dy, z)


PAPER_LAYOUT = DashAndDineLayout(
    red=Base(server=(-1, -9), players=((-5, -10), (-5, -8))),
    blue=Base(server=(-1, 7), players=((-5, 6), (-5, 8))),
    stations={
        "furnace": (2, -1),
        "bowl_chest": (-3, -1),
        "bucket_chest": (-7, -7),
        "egg_chest": (-7, 5),
        "tool_chest": (-11, -1),
        "sugar_cane_farm": (-11, -8),
        "berry_farm": (-11, 6),
        "cocoa_farm": (-15, -8),
        "melon_pumpkin_farm": (-15, -1),
        "beetroot_farm": (-15, 6),
        "carrot_farm": (-19, -8),
        "wheat_farm": (-19, -1),
        "potato_farm": (-19, 6),
    },
)


def mirrored(base: Base) -> Base:
    m = lambda c: (c[0], 2 * MIDDLE_Z - c[1])  # noqa: E731
    return Base(server=m(base.server), players=(m(base.players[0]), m(base.players[1])))


BASE_X = (-6, 3)  # the servers' x (the paper's: -1)
BASE_Z = (7, 11)  # the servers' distance from the middle line (the paper's: 8)
BASE_GAP = 2  # free cells between a base (server, spawns) and any station
DISTANCE = (0.6, 1.4)  # a base's mean distance to the stations, as a share of the paper's


def generate(seed: int) -> DashAndDineLayout:
    """The layout of `seed`: the same on every machine (layout.Draw)."""
    return search(seed, _attempt, problems, "Dash & Dine")


def _attempt(draw: Draw, seed: int) -> DashAndDineLayout | None:
    sx, d = draw.int(*BASE_X), draw.int(*BASE_Z)
    north = Base(server=(sx, MIDDLE_Z - d), players=((sx - 4, MIDDLE_Z - d - 1), (sx - 4, MIDDLE_Z - d + 1)))
    south = mirrored(north)
    red, blue = (north, south) if draw.choice((True, False)) else (south, north)
    taken = _base_cells(red) | _base_cells(blue)
    taken = {
        (x + dx, z + dz)
        for x, z in taken
        for dx in range(-BASE_GAP + 1, BASE_GAP)
        for dz in range(-BASE_GAP + 1, BASE_GAP)
    }
    stations: dict[str, Cell] = {}
    (x0, _, z0), (x1, _, z1) = BOX
    for kind in draw.shuffled(STATIONS):
        for _ in range(100):
            anchor = (draw.int(x0 + 1, x1 - 1), draw.int(z0 + 1, z1 - 1))
            cells = STATIONS[kind].build(*anchor).cells()
            if all(x0 < x < x1 and z0 < z < z1 for x, z in cells) and apart(cells, taken, 1):
                stations[kind] = anchor
                taken |= cells
                break
        else:
            return None
    return DashAndDineLayout(key=seed, red=red, blue=blue, stations={k: stations[k] for k in STATIONS})


def _base_cells(base: Base) -> set[Cell]:
    return {base.server, *base.players}


def mean_distance(layout: DashAndDineLayout, side: str) -> float:
    """A base's mean distance (its server's cell) to the stations' anchors."""
    server = layout.base(side).server
    return sum(math.dist(server, a) for a in layout.stations.values()) / len(layout.stations)


def problems(layout: DashAndDineLayout) -> list[str]:
    """Every way `layout` breaks the rules of docs/layouts.md, one line each (none: valid)."""
    missing = [k for k in STATIONS if k not in layout.stations]
    unknown = [k for k in layout.stations if k not in STATIONS]
    if missing or unknown:
        return [
            f"stations missing: {', '.join(missing) or 'none'}; unknown: {', '.join(unknown) or 'none'} "
            f"(a layout places each of {', '.join(STATIONS)} once)"
        ]
    out = _overlaps(layout, gap=1 if isinstance(layout.key, int) else 0)
    mirror = mirrored(layout.red)
    if mirror.server != layout.blue.server or set(mirror.players) != set(layout.blue.players):
        out.append("the blue base is not the red base mirrored across the middle line (sides must be fair)")
    paper = mean_distance(PAPER_LAYOUT, "red")
    for side in SIDES:
        d = mean_distance(layout, side)
        if not DISTANCE[0] * paper <= d <= DISTANCE[1] * paper and layout.key != PAPER:
            out.append(
                f"{side}'s base is {d:.1f} from the stations on average; the rules keep it "
                f"{DISTANCE[0] * paper:.1f}..{DISTANCE[1] * paper:.1f} (the paper's {paper:.1f})"
            )
    if not out:
        out += unreachable(*_walk_map(layout), bounds=_floor())
    return out


def _floor() -> tuple[Cell, Cell]:
    (x0, _, z0), (x1, _, z1) = BOX
    return (x0, z0), (x1, z1)


def _overlaps(layout: DashAndDineLayout, gap: int) -> list[str]:
    """Stations sharing a cell (generated layouts: also touching: a free cell must lie between)."""
    out: list[str] = []
    seen: dict[str, set[Cell]] = {f"{s} base": _base_cells(layout.base(s)) for s in SIDES}
    (x0, z0), (x1, z1) = _floor()
    for kind, piece in layout.pieces().items():
        cells = piece.cells()
        if not all(x0 < x < x1 and z0 < z < z1 for x, z in cells):
            out.append(f"{kind} at {layout.stations[kind]} does not fit inside the arena {BOX}")
        clash = [name for name, theirs in seen.items() if not apart(cells, theirs, gap)]
        if clash:
            out.append(f"{kind} at {layout.stations[kind]} {'touches' if gap else 'overlaps'} the {clash[0]}")
        seen[kind] = cells
    return out


def _walk_map(layout: DashAndDineLayout) -> tuple[dict, dict, set]:
    """Spawns (both bases' players), targets (every station's worked blocks, both servers) and the
    cells no one walks through."""
    pieces = layout.pieces()
    blocked = {c for p in pieces.values() for c in p.blocked()} | {layout.base(s).server for s in SIDES}
    spawns = {f"{s} player {i}": p for s in SIDES for i, p in enumerate(layout.base(s).players)}
    targets = {kind: p.targets() for kind, p in pieces.items()}
    targets |= {f"{s} server": [layout.base(s).server] for s in SIDES}
    return spawns, targets, blocked
