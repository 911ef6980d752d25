"""What a page's map (js/replay/map.js: the replay page and the layout page) draws at block columns,
read from the canvas's pixels in headless Chromium, beside the colour the map gives each block."""

from __future__ import annotations

import json
from pathlib import Path

from pillagerbench.scenarios.arena import GROUND_Y
from tests.support.browser import run_test_script

GRASS = "grass_block"

READ = """
(function () {
  const m = window.replay.map
  if (%AT% !== null) window.replay.setTime(%AT%)
  const ctx = document.getElementById('map').getContext('2d')
  const probe = document.createElement('canvas').getContext('2d')
  const rgb = (d) => [d[0], d[1], d[2]]
  function colour (name) { probe.fillStyle = m.colourOf(name); probe.fillRect(0, 0, 1, 1); return rgb(probe.getImageData(0, 0, 1, 1).data) }
  const cells = %CELLS%
  const out = {
    cells: cells.map(([x, z, name]) => {
      const [cx, cz] = m.cellCentre(x, z)
      return [x, z, name, colour(name), rgb(ctx.getImageData(Math.floor(cx), Math.floor(cz), 1, 1).data)]
    }),
    markers: window.replay.markers(),
    spawns: Object.fromEntries(%SPAWNS%.map(([name, x, z]) => [name, m.cellCentre(x, z)]))
  }
  const pre = document.createElement('pre'); pre.id = 'test-result'; pre.textContent = JSON.stringify(out)
  document.body.append(pre)
})()
"""


def tops(blocks) -> dict[tuple[int, int], str]:
    """The highest block of each column (at or above the ground's top layer), as a map shows it."""
    best: dict[tuple[int, int], tuple[int, str]] = {}
    for x, y, z, name, *_ in blocks:
        if y >= GROUND_Y and y >= best.get((x, z), (-1, ""))[0]:
            best[(x, z)] = (y, name)
    return {c: name for c, (_, name) in best.items()}


def probe_cells(blocks, others, near: list[tuple[float, float]]) -> list[list]:
    """[x, z, expected top] of every column where `blocks` or `others` (another layout's blocks) have
    something on the ground (grass where only `others` do), leaving out columns a marker (a player's
    disc and label, a mob at `near`) may cover."""
    mine, theirs = tops(blocks), tops(others)
    covered = {(int(x) + dx, int(z) + dz) for x, z in near for dx in range(-3, 11) for dz in range(-3, 4)}
    columns = sorted((set(mine) | set(theirs)) - covered)
    return [[x, z, mine.get((x, z), GRASS)] for x, z in columns]


def drawn(page: Path, cells: list[list], players, at: float | None = None) -> dict:
    """At time `at` (a replay page; None: as the page opens): each cell as [x, z, name, the name's
    colour, the pixel drawn]; the players' markers and the centres of their spawns' cells (canvas
    points, by name); console errors."""
    spawns = [[p.name, p.spawn[0], p.spawn[2]] for p in players]
    script = READ.replace("%CELLS%", json.dumps(cells)).replace("%SPAWNS%", json.dumps(spawns))
    return run_test_script(page, script.replace("%AT%", json.dumps(at)))


def at_spawns(result: dict, slack: float) -> list[str]:
    """The players whose marker is not within `slack` canvas pixels of their spawn's cell centre."""
    markers, spawns = result["markers"], result["spawns"]
    return [
        n
        for n, c in spawns.items()
        if n not in markers or max(map(abs, (markers[n][0] - c[0], markers[n][1] - c[1]))) > slack
    ]
