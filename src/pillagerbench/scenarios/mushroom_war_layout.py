"""Mushroom War's layouts: each side's area (its centre), giant mushrooms, slime patches and player
spawns. `PAPER` is upstream's map (y + 64); `generate(seed)` builds a variant by the rules of
docs/layouts.md; `problems(layout)` checks any layout against those rules.

A giant mushroom is a 2-high stem with 4 cap blocks around its top and 1 above; a slime patch is a
plus of 5 slime blocks. Blue's area is red's mirrored across the arena's middle line, or turned
half a turn about the arena's middle (generated layouts); the paper's is the mirror.
"""

from __future__ import annotations

import math
from typing import Literal

from pydantic import BaseModel, ConfigDict

from pillagerbench.config.sides import SIDES, other_side
from pillagerbench.scenarios.arena import GROUND_Y
from pillagerbench.scenarios.layout import PAPER, Cell, Draw, LayoutKey, apart, search, unreachable

Y = GROUND_Y + 1  # the layer players stand in
BOX = ((-24, 1, -24), (6, Y + 8, 20))
MIDDLE = (-9, -2)  # the box's middle (x, z): the mirror line z = -2, the half-turn's centre
RADIUS = 7  # a team's area: every block within this distance of its centre
PLUS = [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)]
MUSHROOMS, PATCHES, PLAYERS = 3, 3, 2  # per side
SEPARATION = (16, 20)  # distance between the two centres (the paper's: 16)
SPOT_RANGE = 5  # mushrooms and patches sit at most this many cells from the centre on each axis
INNER = RADIUS - 1  # every block of a side's mushrooms and slime is within this distance of its centre
SPAWN_RANGE = 3


class _Frozen(BaseModel):
    model_config = ConfigDict(frozen=True, extra="forbid")


class Area(_Frozen):
    center: Cell  # x, z; players stand at y = Y
    mushrooms: tuple[Cell, ...]  # stems
    slime: tuple[Cell, ...]  # patch centres
    players: tuple[Cell, ...]  # spawns, in the side's player order


class MushroomWarLayout(_Frozen):
    scenario: Literal["mushroom_war"] = "mushroom_war"
    key: LayoutKey = PAPER
    red: Area
    blue: Area
    symmetry: Literal["mirror", "half_turn"] = "mirror"

    def area(self, side: str) -> Area:
        return self.red if side == "red" else self.blue


def mirror(cell: Cell) -> Cell:
    return (cell[0], 2 * MIDDLE[1] - cell[1])


def half_turn(cell: Cell) -> Cell:
    return (2 * MIDDLE[0] - cell[0], 2 * MIDDLE[1] - cell[1])


SYMMETRIES = {"mirror": mirror, "half_turn": half_turn}


def _mapped(area: Area, f) -> Area:
    return Area(
        center=f(area.center),
        mushrooms=tuple(map(f, area.mushrooms)),
        slime=tuple(map(f, area.slime)),
        players=tuple(map(f, area.players)),
    )


PAPER_LAYOUT = MushroomWarLayout(
    red=Area(
        center=(-9, -10),
        mushrooms=((-13, -8), (-5, -8), (-9, -12)),
        slime=((-9, -8), (-13, -12), (-5, -12)),
        players=((-7, -10), (-11, -10)),
    ),
    blue=Area(
        center=(-9, 6),
        mushrooms=((-13, 4), (-5, 4), (-9, 8)),
        slime=((-9, 4), (-13, 8), (-5, 8)),
        players=((-11, 6), (-7, 6)),
    ),
)


def stems(area: Area) -> list[tuple[int, int, int]]:
    return [(x, y, z) for x, z in area.mushrooms for y in (Y, Y + 1)]


def caps(area: Area) -> list[tuple[int, int, int]]:
    return [(x + dx, Y + 1, z + dz) for x, z in area.mushrooms for dx, dz in PLUS[1:]] + [
        (x, Y + 2, z) for x, z in area.mushrooms
    ]


def slime(area: Area) -> list[tuple[int, int, int]]:
    return [(x + dx, Y, z + dz) for x, z in area.slime for dx, dz in PLUS]


def plus(cell: Cell) -> list[Cell]:
    return [(cell[0] + dx, cell[1] + dz) for dx, dz in PLUS]


def generate(seed: int) -> MushroomWarLayout:
    """The layout of `seed`: the same on every machine (layout.Draw)."""
    return search(seed, _attempt, problems, "Mushroom War")


def _attempt(draw: Draw, seed: int) -> MushroomWarLayout | None:
    half = draw.int(SEPARATION[0] // 2, SEPARATION[1] // 2)
    north = draw.choice((True, False))
    cx, cz = MIDDLE[0] + draw.int(-3, 3), MIDDLE[1] + (-half if north else half)
    forbidden: set[Cell] = set()  # offsets from the centre: the spots placed so far and the cells around them
    spots = []
    for _ in range(MUSHROOMS + PATCHES):
        options = [o for o in SPOTS if not forbidden.intersection(plus(o))]
        if not options:
            return None
        spots.append(draw.choice(options))
        forbidden |= grown(plus(spots[-1]))
    spawns = []
    for _ in range(PLAYERS):
        options = [o for o in SPAWNS if o not in forbidden]
        if not options:
            return None
        spawns.append(draw.choice(options))
        forbidden |= grown([spawns[-1]])
    at = lambda o: (cx + o[0], cz + o[1])  # noqa: E731
    red = Area(
        center=(cx, cz),
        mushrooms=tuple(map(at, spots[:MUSHROOMS])),
        slime=tuple(map(at, spots[MUSHROOMS:])),
        players=tuple(map(at, spawns)),
    )
    symmetry = draw.choice(SYMMETRIES)
    return MushroomWarLayout(key=seed, red=red, blue=_mapped(red, SYMMETRIES[symmetry]), symmetry=symmetry)


def grown(cells: list[Cell]) -> set[Cell]:
    """The cells and every cell beside them (diagonals too)."""
    return {(x + dx, z + dz) for x, z in cells for dx in (-1, 0, 1) for dz in (-1, 0, 1)}


def _inside(cells: list[Cell], dy: int = 0) -> bool:
    return all(math.dist((x, dy, z), (0, 0, 0)) <= INNER for x, z in cells)


# where a mushroom or a patch may sit (offsets from the centre): all its blocks inside, the centre free
SPOTS = [
    (dx, dz)
    for dx in range(-SPOT_RANGE, SPOT_RANGE + 1)
    for dz in range(-SPOT_RANGE, SPOT_RANGE + 1)
    if max(abs(dx), abs(dz)) >= 2 and _inside(plus((dx, dz)), dy=2)
]
SPAWNS = [(dx, dz) for dx in range(-SPAWN_RANGE, SPAWN_RANGE + 1) for dz in range(-SPAWN_RANGE, SPAWN_RANGE + 1)]


def problems(layout: MushroomWarLayout) -> list[str]:
    """Every way `layout` breaks the rules of docs/layouts.md, one line each (none: valid)."""
    out = []
    for side in SIDES:
        area, other = layout.area(side), layout.area(other_side(side))
        counts = (len(area.mushrooms), len(area.slime), len(area.players))
        if counts != (MUSHROOMS, PATCHES, PLAYERS):
            out.append(
                f"{side}: {counts[0]} mushrooms, {counts[1]} slime patches, {counts[2]} players; "
                f"expected {MUSHROOMS}, {PATCHES}, {PLAYERS}"
            )
        blocks = caps(area) + stems(area) + slime(area)
        far = [b for b in blocks if math.dist(b, (area.center[0], Y, area.center[1])) > INNER]
        if far:
            out.append(f"{side}: blocks outside its area (farther than {INNER} from {area.center}): {far[:3]}")
        near = [b for b in blocks if math.dist(b, (other.center[0], Y, other.center[1])) <= RADIUS + 1]
        if near:
            out.append(f"{side}: blocks within the other side's area: {near[:3]}")
    out += _overlaps(layout) + _bounds(layout) + _fairness(layout)
    if not out:
        out += unreachable(*_walk_map(layout), bounds=_floor())
    return out


def _footprints(layout: MushroomWarLayout) -> dict[str, list[Cell]]:
    out: dict[str, list[Cell]] = {}
    for side in SIDES:
        area = layout.area(side)
        out |= {f"{side} mushroom {i}": plus(c) for i, c in enumerate(area.mushrooms)}
        out |= {f"{side} slime patch {i}": plus(c) for i, c in enumerate(area.slime)}
    return out


def _overlaps(layout: MushroomWarLayout) -> list[str]:
    out: list[str] = []
    seen: dict[str, list[Cell]] = {}
    for name, cells in _footprints(layout).items():
        clash = [other for other, theirs in seen.items() if not apart(cells, set(theirs), 1)]
        if clash:
            out.append(f"{name} overlaps or touches {clash[0]} (a free cell must lie between them)")
        seen[name] = cells
    taken = {c for cells in _footprints(layout).values() for c in cells}
    for side in SIDES:
        for spawn in layout.area(side).players:
            if not apart([spawn], taken, 1):
                out.append(f"{side} spawn {spawn} is on or beside a mushroom or slime patch")
    return out


def _floor() -> tuple[Cell, Cell]:
    (x0, _, z0), (x1, _, z1) = BOX
    return (x0, z0), (x1, z1)


def _bounds(layout: MushroomWarLayout) -> list[str]:
    (x0, z0), (x1, z1) = _floor()
    out = []
    for side in SIDES:
        c = layout.area(side).center
        if not (x0 + RADIUS < c[0] < x1 - RADIUS and z0 + RADIUS < c[1] < z1 - RADIUS):
            out.append(f"{side}: its area (centre {c}) does not fit in the arena {BOX}")
    sep = math.dist(layout.red.center, layout.blue.center)
    if not SEPARATION[0] <= sep <= SEPARATION[1]:
        out.append(f"the areas' centres are {sep:.1f} apart; the rules keep them {SEPARATION[0]}..{SEPARATION[1]}")
    return out


def _fairness(layout: MushroomWarLayout) -> list[str]:
    """Blue is red mapped by the layout's symmetry (its spawns in any order: the paper's are red's
    mirrored in the other order)."""
    mapped = _mapped(layout.red, SYMMETRIES[layout.symmetry])
    if mapped.model_copy(update={"players": ()}) == layout.blue.model_copy(update={"players": ()}) and set(
        mapped.players
    ) == set(layout.blue.players):
        return []
    return [f"blue is not the {layout.symmetry.replace('_', ' ')} of red (sides must be fair by construction)"]


def _walk_map(layout: MushroomWarLayout) -> tuple[dict, dict, set]:
    """Spawns, targets (every cap and slime block, both sides) and the cells no one can walk through
    (a mushroom's stem and caps, a slime block: one could jump onto slime, but the check does not count on it)."""
    footprints = _footprints(layout)
    blocked = {c for cells in footprints.values() for c in cells}
    spawns = {f"{side} player {i}": p for side in SIDES for i, p in enumerate(layout.area(side).players)}
    return spawns, footprints, blocked
