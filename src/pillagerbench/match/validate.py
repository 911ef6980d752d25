"""The checks of the groups a run configuration chooses by name, registered into the one validation
(config/validate.py `GROUP_CHECKS`; importing `pillagerbench.match` registers them): the scenario against
its registry; `layout=` and `split=`; each side's team, its options against its options model
(`Team.Options`: keys, types, ranges; teams/options.py), `red.llm.*` / `blue.llm.*` only for teams that
use an LLM, and the LLM settings of every side that uses one. Each takes the choices typed
(config/schema.py `Choices`) and gives one line per problem, naming the key, the bad value and what is valid.
"""

from __future__ import annotations

from pillagerbench.config import people
from pillagerbench.config.compose import ConfigError
from pillagerbench.config.schema import Choices, problems
from pillagerbench.config.sides import SIDES
from pillagerbench.config.validate import GROUP_CHECKS, LAYOUT, SCENARIO, TEAMS
from pillagerbench.llm.errors import LLMConfigError
from pillagerbench.llm.prices import price_problem
from pillagerbench.llm.settings import LLMSettings
from pillagerbench.scenarios import SCENARIOS, make_scenario
from pillagerbench.scenarios.layout import PAPER, LayoutError, parse_layout, parse_split
from pillagerbench.teams import TEAMS as TEAM_CLASSES
from pillagerbench.teams import find_team
from pillagerbench.teams.options import defaults, options_model


def _team_problems(choices: Choices, side: str) -> list[str]:
    node, scenario = choices.side(side), choices.scenario.name
    name = node.name
    try:
        cls = find_team(name)
    except ConfigError as exc:
        return [f"{side}={name}: {exc}"]
    out = []
    if cls.scenarios is not None and scenario not in cls.scenarios:
        valid = [n for n, c in TEAM_CLASSES.items() if c.scenarios is None or scenario in c.scenarios]
        out.append(
            f"{side}={name}: plays only {', '.join(cls.scenarios)}, not {scenario}; "
            f"teams for {scenario}: {', '.join(valid)}"
        )
    model = options_model(cls)
    declared = defaults(model)
    given = node.options
    found = problems(model, given, side)
    out += [
        p + (f" (options of {name}: {', '.join(declared) or 'none'})" if p.endswith("unknown key") else "")
        for p in found
    ]
    if not found:
        out += [f"{side}.{p}" for p in cls.check_options({**declared, **given})]
    if node.llm.given() and not cls.uses_llm:
        llm_teams = [n for n, c in TEAM_CLASSES.items() if c.uses_llm]
        for key in node.llm.given():
            out.append(f"{side}.llm.{key}: team {name} uses no LLM (teams that do: {', '.join(llm_teams)})")
    elif cls.uses_llm:
        out += _llm_problems(choices, side)
    return out


def _llm_problems(choices: Choices, side: str) -> list[str]:
    """The LLM settings `side` plays with; settings that cannot work (llm=inspect without its extra);
    a dollar budget needs a known price."""
    merged, where = choices.llm_of(side), f"{side}.llm" if choices.side(side).llm.given() else "llm"
    found = merged.problems(where)
    if found:
        return found
    try:
        return [p for p in [price_problem(LLMSettings.from_config(merged), where)] if p]
    except LLMConfigError as exc:
        return [exc.detail]


@GROUP_CHECKS.register(SCENARIO)
def scenario_problems(choices: Choices) -> list[str]:
    """`scenario=`: a registered scenario."""
    name = choices.scenario.name
    return [] if name in SCENARIOS else [f"scenario={name}: {SCENARIOS.unknown(name)}"]


@GROUP_CHECKS.register(TEAMS)
def sides_problems(choices: Choices) -> list[str]:
    """Both sides: their teams, options and LLM settings (the shared llm settings' problems once)."""
    found: list[str] = []
    for side in SIDES:
        found += [p for p in _team_problems(choices, side) if p not in found]
    return found + people_problems(choices)


def people_problems(choices: Choices) -> list[str]:
    """`red.humans=[...]` names the side's own players; people play on the real clock (config/people.py)."""
    scenario = choices.scenario.name
    if scenario not in SCENARIOS:
        return []
    sides = {s.key: list(s.player_names) for s in make_scenario(scenario).sides}
    nodes = {side: {"name": choices.side(side).name, **(choices.side(side).model_extra or {})} for side in SIDES}
    found = [p for side in SIDES for p in people.side_problems(side, nodes[side], sides[side])]
    seats = {
        side: people.seats_of(nodes[side]["name"], nodes[side].get(people.SIDE_KEY), sides[side]) for side in SIDES
    }
    return found or people.clock_problems(choices.clock.mode, seats)


@GROUP_CHECKS.register(LAYOUT)
def layout_problems(choices: Choices) -> list[str]:
    """`layout=` and `split=`: a known value, one or the other, and a layout of the chosen scenario."""
    layout, split = choices.layout, choices.split
    try:
        parse_split(split)
        key = parse_layout(layout)
        if split is not None and key != PAPER:
            return [f"split={split} plays each episode on a layout of its own; drop layout={layout} or split={split}"]
        scenario = choices.scenario.name
        if scenario in SCENARIOS and not isinstance(key, int):  # a seed's layout is valid by construction
            SCENARIOS[scenario].layouts.make(key)
    except LayoutError as exc:
        return [str(exc)]
    return []
