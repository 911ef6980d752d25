"""Before episode 0: every LLM the run needs answers (llm/preflight.py) and every team that can
check itself does (Team.preflight, e.g. a remote team's server). One line per problem; nothing is
created before this passes."""

from __future__ import annotations

import asyncio
from collections.abc import Iterable
from typing import Any

from pillagerbench.config.compose import ConfigError
from pillagerbench.config.schema import RunConfig
from pillagerbench.config.sides import SIDES
from pillagerbench.llm.preflight import preflight as llm_preflight
from pillagerbench.teams import find_team


def sides_of(cfg: RunConfig) -> list[tuple[str, dict, Any]]:
    """(team name, options, llm config or None) for both sides of a match config."""
    out = []
    for side in SIDES:
        team = cfg.side(side)
        uses_llm = getattr(find_team(team.name), "uses_llm", False)
        out.append((team.name, team.options, cfg.llm_of(side) if uses_llm else None))
    return out


async def problems(sides: Iterable[tuple[str, dict, Any]]) -> list[str]:
    sides = list(sides)
    teams: dict[str, tuple[str, dict]] = {}
    for name, options, _ in sides:
        teams.setdefault(f"{name}{sorted(options.items())!r}", (name, options))
    checks = [find_team(name).preflight(options) for name, options in teams.values()]
    llms, team_problems = await asyncio.gather(
        llm_preflight([llm for _, _, llm in sides if llm is not None]), asyncio.gather(*checks)
    )
    return list(llms) + [p for p in team_problems if p]


def check(sides: Iterable[tuple[str, dict, Any]]) -> None:
    found = asyncio.run(problems(sides))
    if found:
        raise ConfigError("\n".join(found))
