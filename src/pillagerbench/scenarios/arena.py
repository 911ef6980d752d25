"""An arena as data, and building it (or putting it back) in place through the control channel.

Coordinates are Minecraft 1.16.5 ones: upstream's 1.19.4 coordinates with y shifted by +64
(`up64`), so the flat ground's top is y = 3 and players stand at y = 4.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from pillagerbench.server.seams import Control

Pos = tuple[int, int, int]
GROUND_Y = 3
Y_SHIFT = 64  # upstream (1.19.4, ground -61) -> ours (1.16.5, ground 3)
FILL_LIMIT = 32768


def standing(cell: tuple[int, int]) -> Pos:
    """A floor cell (x, z) as the block position a player stands in."""
    return (cell[0], GROUND_Y + 1, cell[1])


def up64(x: float, y: float, z: float) -> tuple:
    """Upstream coordinates to ours."""
    return (x, y + Y_SHIFT, z)


@dataclass
class Arena:
    """Everything a scenario puts into the flat world.

    box: the (min, max) corners restored on reset — columns from y=1 (dirt) to the top of the box.
    blocks: (x, y, z, name, properties?) placed after the box is cleared.
    """

    box: tuple[Pos, Pos]
    blocks: list[tuple] = field(default_factory=list)
    chests: dict[Pos, dict[str, int]] = field(default_factory=dict)
    furnaces: dict[Pos, dict[str, Any]] = field(default_factory=dict)
    mobs: Sequence[tuple[str, tuple[float, float, float]]] = field(default_factory=list)
    egg_farms: list[tuple[Pos, float]] = field(default_factory=list)  # (chest, a chicken lays every s..2s s)

    async def build(self, server: Control) -> None:
        """Build the arena, or put it back exactly as it was built (chests, crops, mobs, items)."""
        await server.reset_state()
        (x0, y0, z0), (x1, y1, z1) = self.box
        layers = [(1, 2, "dirt"), (GROUND_Y, GROUND_Y, "grass_block"), (GROUND_Y + 1, y1, "air")]
        for lo, hi, name in layers:
            for a, b in _split([x0, lo, z0], [x1, hi, z1]):
                await server.fill(a, b, name)
        for batch in _batched(self.blocks, 2000):
            await server.set_blocks([list(b) for b in batch])
        for pos, items in self.chests.items():
            await server.set_chest(list(pos), items)
        for pos, contents in self.furnaces.items():
            await server.set_furnace(list(pos), **contents)
        for name, at in self.mobs:
            await server.summon(name, list(at))
        for chest, interval in self.egg_farms:
            await server.egg_farm(list(chest), interval)


def _split(a: list[int], b: list[int]):
    """Cut a box into slabs that each fit one fill request."""
    (x0, y0, z0), (x1, y1, z1) = a, b
    per_x = (y1 - y0 + 1) * (z1 - z0 + 1)
    step = max(1, FILL_LIMIT // per_x)
    for xs in range(x0, x1 + 1, step):
        yield [xs, y0, z0], [min(x1, xs + step - 1), y1, z1]


def _batched(items, n):
    it = iter(items)
    while batch := list(itertools.islice(it, n)):
        yield batch
