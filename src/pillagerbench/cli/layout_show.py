"""`pillagerbench layout show SCENARIO LAYOUT`: a picture of a layout's map, to look at a variant
before playing it. LAYOUT is what `layout=` takes: paper, a seed, or a layout file (.json). The
picture is one self-contained HTML page (it loads nothing) drawing the arena as built, top-down, as
the replay page draws a recording (js/replay/map.js): blocks, mobs and every player at its spawn,
with what the chests and furnaces hold. `--json` writes the layout itself instead, a file that
`layout=FILE.json` plays (edit it to make your own; docs/layouts.md says the rules it must keep).

    pillagerbench layout show mushroom_war 42                 # writes layout_mushroom_war_42.html
    pillagerbench layout show dash_and_dine paper --out map.html
    pillagerbench layout show mushroom_war 42 --json          # writes layout_mushroom_war_42.json
"""

from __future__ import annotations

import json
from pathlib import Path

from pillagerbench.config.args import Parser
from pillagerbench.replay.map_page import render_still, still_data
from pillagerbench.scenarios import SCENARIOS, Scenario, make_scenario
from pillagerbench.scenarios.arena import GROUND_Y, Arena
from pillagerbench.scenarios.layout import PAPER, LayoutError, parse_layout


def parser() -> Parser:
    p = Parser(prog="pillagerbench layout", description=__doc__.split("\n\n")[0])
    p.add_argument("action", choices=["show"], help="show: write a picture of the layout's map")
    p.add_argument("scenario", help=f"the scenario: {', '.join(SCENARIOS)}")
    p.add_argument("layout", metavar="SEED|paper|FILE.json", help="the layout, as layout= takes it")
    p.add_argument("--out", metavar="PATH", help="where to write (default: layout_SCENARIO_LAYOUT.html or .json)")
    p.add_argument("--json", action="store_true", help="write the layout as JSON (for layout=FILE.json), not a page")
    return p


def scenario_on(name: str, value: str) -> Scenario:
    """The scenario on the layout `value`; a bad name or layout is one line (a ConfigError)."""
    scenario = make_scenario(name)
    try:
        return scenario.with_layout(parse_layout(value))
    except LayoutError as exc:
        raise LayoutError(" ".join(str(exc).split())) from None


def layout_json(scenario: Scenario) -> str:
    return json.dumps({"scenario": scenario.key, **scenario.layout.model_dump(mode="json")}, indent=1) + "\n"


def notes(scenario: Scenario, arena: Arena) -> list[str]:
    """What the map cannot show: where it lies, the spawns, the chests' and furnaces' contents, the mobs."""
    (x0, _, z0), (x1, _, z1) = arena.box
    out = [f"top-down, north (-z) up, east (+x) right: x {x0}..{x1}, z {z0}..{z1}; players stand at y = {GROUND_Y + 1}"]
    out += [
        f"{side.key}: " + ", ".join(f"{p.name} at {p.spawn}" for p in side.players) + f"; centre {side.center}"
        for side in scenario.sides
    ]
    out += [f"{p.name} at {p.spawn}" for p in scenario.extra_players]
    out += [f"chest at {pos}: {_listed(items) or 'empty'}" for pos, items in arena.chests.items()]
    out += [f"furnace at {pos}: {_listed(contents)}" for pos, contents in arena.furnaces.items()]
    out += [f"egg farm: the chickens lay into the chest at {chest}" for chest, _ in arena.egg_farms]
    mobs: dict[str, int] = {}
    for name, _ in arena.mobs:
        mobs[name] = mobs.get(name, 0) + 1
    return out + [f"{count} {name}" for name, count in mobs.items()]


def _listed(contents: dict) -> str:
    """{"bowl": 64} -> "bowl 64"; {"fuel": ["coal", 64]} -> "fuel coal 64"."""
    return ", ".join(" ".join(map(str, [k, *(v if isinstance(v, list) else [v])])) for k, v in contents.items())


def layout_page(scenario: Scenario) -> str:
    arena = scenario.arena
    data = still_data(
        arena.box,
        arena.blocks,
        arena.mobs,
        [(p.name, p.spawn) for p in scenario.all_players()],
        {side.key: side.player_names for side in scenario.sides},
    )
    key = scenario.layout_key
    title = f"{scenario.title}, layout {key} ({scenario.split})"
    play = f"play it: pillagerbench run scenario={scenario.key} layout={key}"
    return render_still(data, title, [*notes(scenario, arena), play])


def default_out(scenario: Scenario, as_json: bool) -> Path:
    key = scenario.layout_key
    name = str(key) if isinstance(key, int) or key == PAPER else Path(key).stem
    return Path(f"layout_{scenario.key}_{name}.{'json' if as_json else 'html'}")


def main(argv: list[str]) -> int:
    a = parser().parse_args(argv)
    scenario = scenario_on(a.scenario, a.layout)
    out = Path(a.out) if a.out else default_out(scenario, a.json)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(layout_json(scenario) if a.json else layout_page(scenario))
    print(f"layout: {out}")
    return 0
