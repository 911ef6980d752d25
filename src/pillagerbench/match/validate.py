"""The whole run configuration checked at once, before anything is created or started.

The top-level keys are typed (config/schema.py); a team's options are checked against its options
model (`Team.Options`: keys, types, ranges; teams/options.py); `red.llm.*` / `blue.llm.*` only for
teams that use an LLM; the LLM settings of every side that uses one. Every problem is one line naming the key, the bad value and what is
valid; `check_run_config` raises one `ConfigError` holding all of them, or returns the typed
configuration (config/schema.py RunConfig) every layer below takes. Each check reads the configuration
as plain data (a composed DictConfig or a stored dict), since it may be any value the user wrote.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from pillagerbench.config.compose import ConfigError
from pillagerbench.config.schema import (
    LLMConfig,
    RunConfig,
    check,
    clock_problems,
    plain,
    problems,
    top_level_problems,
    watch_problems,
)
from pillagerbench.config.schema import merged as merged_llm
from pillagerbench.config.sides import SIDES
from pillagerbench.llm.errors import LLMConfigError
from pillagerbench.llm.prices import price_problem
from pillagerbench.llm.settings import LLMSettings
from pillagerbench.scenarios import SCENARIOS
from pillagerbench.scenarios.layout import PAPER, LayoutError, parse_layout, parse_split
from pillagerbench.teams import TEAMS, find_team
from pillagerbench.teams.options import defaults, options_model

Composed = Mapping[str, Any]  # a composed configuration (a dict, or Hydra's node) before it is typed


def _team_problems(data: dict[str, Any], side: str, scenario: str) -> list[str]:
    node = data[side]
    name = str(node.get("name"))
    try:
        cls = find_team(name)
    except ConfigError as exc:
        return [f"{side}={name}: {exc}"]
    out = []
    if cls.scenarios is not None and scenario not in cls.scenarios:
        valid = [n for n, c in TEAMS.items() if c.scenarios is None or scenario in c.scenarios]
        out.append(
            f"{side}={name}: plays only {', '.join(cls.scenarios)}, not {scenario}; "
            f"teams for {scenario}: {', '.join(valid)}"
        )
    model = options_model(cls)
    declared = defaults(model)
    given = {k: v for k, v in node.items() if k not in ("name", "llm")}
    found = problems(model, given, side)
    out += [
        p + (f" (options of {name}: {', '.join(declared) or 'none'})" if p.endswith("unknown key") else "")
        for p in found
    ]
    if not found:
        out += [f"{side}.{p}" for p in cls.check_options({**declared, **given})]
    own_llm = node.get("llm") or {}
    if own_llm and not cls.uses_llm:
        llm_teams = [n for n, c in TEAMS.items() if c.uses_llm]
        for key in own_llm:
            out.append(f"{side}.llm.{key}: team {name} uses no LLM (teams that do: {', '.join(llm_teams)})")
    elif cls.uses_llm:
        merged = merged_llm(data["llm"], own_llm)
        where = f"{side}.llm" if own_llm else "llm"
        found_llm = problems(LLMConfig, merged, where)
        out += found_llm
        if (
            not found_llm
        ):  # settings that cannot work (llm=inspect without its extra); a dollar budget needs a known price
            try:
                out += [p for p in [price_problem(LLMSettings.from_config(merged), where)] if p]
            except LLMConfigError as exc:
                out.append(exc.detail)
    return out


def team_problems(cfg: Composed) -> list[str]:
    """Problems of a match config's scenario and both sides (teams, options, LLM settings)."""
    found: list[str] = []
    data = plain(cfg)
    scenario = str(data["scenario"]["name"])
    if scenario not in SCENARIOS:
        found.append(f"scenario={scenario}: {SCENARIOS.unknown(scenario)}")
    for side in SIDES:
        for p in _team_problems(data, side, scenario):
            if p not in found:  # the shared llm settings are reported once
                found.append(p)
    return found


def layout_problems(cfg: Composed) -> list[str]:
    """`layout=` and `split=`: a known value, one or the other, and a layout of the chosen scenario."""
    data = plain(cfg)
    layout, split = data.get("layout", PAPER), data.get("split")
    try:
        parse_split(split)
        key = parse_layout(layout)
        if split is not None and key != PAPER:
            return [f"split={split} plays each episode on a layout of its own; drop layout={layout} or split={split}"]
        scenario = str(data["scenario"]["name"])
        if scenario in SCENARIOS and not isinstance(key, int):  # a seed's layout is valid by construction
            SCENARIOS[scenario].layouts.make(key)
    except LayoutError as exc:
        return [str(exc)]
    return []


def check_run_config(cfg: Composed, *, teams: bool = True) -> RunConfig:
    """The typed configuration of `cfg`, or one ConfigError listing every problem of it (one line
    each). With teams=False (experiments choose teams themselves, see experiments/runner.check_series)
    only the top-level keys are checked."""
    data = plain(cfg)
    top = top_level_problems(data)
    watch = [] if any(line.startswith("watch=") for line in top) else watch_problems(data)
    if not teams and data.get("watch") is not None:  # an experiment: many servers at once
        watch = [f"watch={data['watch']}: the live view shows one match; experiments play many series at once"]
    check(top + watch + clock_problems(data) + layout_problems(data) + (team_problems(data) if teams else []))
    return RunConfig.of(data)
