"""People in the arena (docs/people.md): which players people play, and the checks of it.

- `red=human`: a team whose every player is a person (teams/human.py);
- `red.humans=[Ryn]`: the named players of a side are people, the rest its team's agents;
- `humans.port`, `humans.ready_timeout_s`: the people's page (0 = a free port) and how long the match waits,
  before the first episode, for every person to be ready;
- `humans.client`: `page` (people play from the browser) or `minecraft` (from a Minecraft Java 1.16.5 client,
  joining at the address the run prints under the player's name: people/client.py; `humans.port` is then
  that address's port).

People play on the real clock: `clock=lockstep` with any person is refused (a person cannot wait for a
world held tick by tick). A person's own name, typed on the page, follows Minecraft's player-name rules
(`PLAYER_NAME`).
"""

from __future__ import annotations

import re
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

HUMAN_TEAM = "human"  # the team whose players are all people
SIDE_KEY = "humans"  # red.humans=[NAME, ...]: the side's players played by people
CLIENTS = ("page", "minecraft")  # humans.client: what a person plays from
PLAYER_NAME = re.compile(r"[A-Za-z0-9_]{3,16}")  # Minecraft Java's player names


class HumansConfig(BaseModel):
    """The top-level `humans` node (conf/config.yaml)."""

    model_config = ConfigDict(extra="forbid")

    port: int = Field(ge=0, le=65535)
    ready_timeout_s: float = Field(gt=0, allow_inf_nan=False)
    client: Literal["page", "minecraft"] = "page"  # CLIENTS; runs from before the key: the page


def name_problem(name: object) -> str | None:
    """Why `name` is not a valid player name, or None."""
    if isinstance(name, str) and PLAYER_NAME.fullmatch(name):
        return None
    return f"{name!r} is not a player name (3 to 16 letters, digits or _)"


def seats_of(team: str, humans: object, players: list[str]) -> list[str]:
    """The players of a side (its team's name, its `humans`, its scenario players) that people play."""
    if team == HUMAN_TEAM:
        return list(players)
    given = humans or []
    return [str(n) for n in given] if isinstance(given, (list, tuple)) else []


def side_problems(side: str, node: dict[str, Any], players: list[str]) -> list[str]:
    """`red.humans`: a list of the side's own players, each once."""
    given = node.get(SIDE_KEY)
    if given is None:
        return []
    if not isinstance(given, (list, tuple)):
        return [f"{side}.humans={given!r}: a list of the side's players (one of {', '.join(players)})"]
    out = [
        f"{side}.humans: {n!r} is not a player of {side} (its players: {', '.join(players)})"
        for n in given
        if str(n) not in players
    ]
    if len({str(n) for n in given}) != len(given):
        out.append(f"{side}.humans={list(given)!r}: a player is named twice")
    return out


def clock_problems(mode: str, seats: dict[str, list[str]]) -> list[str]:
    """People play on the real clock (`mode`: the run's clock)."""
    if mode != "lockstep" or not any(seats.values()):
        return []
    who = ", ".join(f"{side}: {', '.join(names)}" for side, names in seats.items() if names)
    return [f"clock=lockstep: people play on the real clock ({who}); drop clock=lockstep or the humans"]
