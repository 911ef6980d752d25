"""`pillagerbench layout show SCENARIO LAYOUT`: a picture of a layout's map, to look at a variant
before playing it. LAYOUT is what `layout=` takes: paper, a seed, or a layout file (.json). The
picture is one self-contained HTML page (it loads nothing) drawing the arena as built, top-down, as
the replay page draws a recording (js/replay/map.js): blocks, mobs and every player at its spawn,
with what the chests and furnaces hold (people/lobby.py builds it: the people's lobby shows the same
page). `--json` writes the layout itself instead, a file that `layout=FILE.json` plays (edit it to
make your own; docs/layouts.md says the rules it must keep).

    pillagerbench layout show mushroom_war 42                 # writes layout_mushroom_war_42.html
    pillagerbench layout show dash_and_dine paper --out map.html
    pillagerbench layout show mushroom_war 42 --json          # writes layout_mushroom_war_42.json
"""

from __future__ import annotations

import json
from pathlib import Path

from pillagerbench.config.args import Parser
from pillagerbench.people.lobby import layout_page
from pillagerbench.scenarios import SCENARIOS, Scenario, make_scenario
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
