"""A page with only the map, drawn as the replay page draws a recording's (js/replay/map.js): the
world at one moment, given as blocks, mobs and players rather than read from a recording. It is
how `pillagerbench layout show` pictures a layout before anyone plays on it. Self-contained: the
script and style are inline, the page loads nothing.
"""

from __future__ import annotations

import html
from collections.abc import Iterable

from pillagerbench.replay.page import STYLE, embedded, script
from pillagerbench.replay.record import GROUND_Y

Pos = tuple[float, float, float]


def still_data(
    box: tuple[tuple[int, int, int], tuple[int, int, int]],
    blocks: Iterable[tuple],
    mobs: Iterable[tuple[str, Pos]],
    players: Iterable[tuple[str, Pos]],
    sides: dict[str, list[str]],
) -> dict:
    """The replay page's data (page.page_data's shape) for a world at rest: the flat ground under
    `box` with `blocks` (x, y, z, name, ...) on it, `mobs` (name, position), `players` (name, the
    block they stand on) and `sides` (side -> its players' names)."""
    (x0, _, z0), (x1, y1, z1) = box
    world = {(x, GROUND_Y, z): "grass_block" for x in range(x0, x1 + 1) for z in range(z0, z1 + 1)}
    world |= {tuple(b[:3]): b[3] for b in blocks if b[1] >= GROUND_Y}
    palette: dict[str, int] = {}
    rows = [[*pos, palette.setdefault(name, len(palette))] for pos, name in sorted(world.items())]
    return {
        "map": {
            "box": [[x0, GROUND_Y, z0], [x1, y1, z1]],
            "palette": list(palette),
            "blocks": rows,
            "ground": GROUND_Y,
        },
        "changes": [],
        "items": [],
        "mobs": [{"name": n, "pos": list(p), "health": None, "from": 0, "to": 1} for n, p in mobs],
        "tracks": {n: [[0, p[0] + 0.5, p[1], p[2] + 0.5, 0, None]] for n, p in players},
        "sides": {k: {"players": names} for k, names in sides.items()},
    }


def render_still(data: dict, title: str, notes: Iterable[str] = ()) -> str:
    """The page: a title, the map with its legend, and a line per note (plain text)."""
    items = "".join(f"<li>{html.escape(n)}</li>" for n in notes)
    return (
        f"<!doctype html><html><head><meta charset='utf-8'><title>{html.escape(title)}</title>"
        f"<style>{STYLE}</style></head><body><h1>{html.escape(title)}</h1>"
        "<canvas id='map'></canvas><div id='legend'></div>"
        f"<ul class='note'>{items}</ul>" + embedded(data) + f"<script>{script('map_page.js')}</script></body></html>"
    )
