"""`agent`: the team whose players an agent outside the benchmark plays through the game's tools, from a
seat (`seat.py`) that a front opened in this process: `pillagerbench mcp` (the MCP client's team) or
Inspect's `-T team=agent` (the Inspect agent's). Its identity is the agent's (teams/entrant.py): the
name and version the agent declares and, when given, its model.
"""

from __future__ import annotations

import json
import secrets
from typing import Any

from pydantic import Field

from pillagerbench.teams.base import Team, TeamContext
from pillagerbench.teams.tools.seat import Seat, SeatOptions

# the seats the fronts of this process opened (`open_seat`), by id: how the team a config names finds its agent
# (None: reserved, so a config naming it can be checked before the seat, which needs the config's scenario)
SEATS: dict[str, Seat | None] = {}


def reserve_seat() -> str:
    key = f"seat-{len(SEATS) + 1}-{secrets.token_hex(4)}"
    SEATS[key] = None
    return key


def open_seat(seat: Seat, key: str | None = None) -> str:
    key = key or reserve_seat()
    SEATS[key] = seat
    return key


class AgentOptions(SeatOptions):
    """agent's options: who the agent is (set by the front that seats it), and its seat's timings."""

    agent: str = Field(default="unknown", description="the agent's declared name (MCP clientInfo, the solver's)")
    agent_version: str = Field(default="0", description="the agent's declared version")
    agent_model: str | None = Field(default=None, description="the model behind the agent, when known")
    seat: str | None = Field(default=None, description="the seat a front of this process opened (not play)")


class AgentTeam(Team):
    name = "agent"
    Options = AgentOptions

    def __init__(self, **options: object):
        super().__init__(**options)
        self.settings = AgentOptions.model_validate(options)

    @classmethod
    def check_options(cls, options: dict[str, Any]) -> list[str]:
        seat = options.get("seat")
        if seat is None or seat not in SEATS:
            return [
                "the agent team is played by an agent through the game's tools: start it with `pillagerbench mcp` "
                "or Inspect's `-T team=agent` (docs/any-agent.md), not with red=agent"
            ]
        return []

    @property
    def seat(self) -> Seat:
        found = SEATS.get(self.settings.seat or "")
        if found is None:
            raise RuntimeError(f"no seat {self.settings.seat!r} in this process (docs/any-agent.md)")
        return found

    async def pre_game(self, ctx: TeamContext) -> None:
        seat = self.seat
        seat.configure(self.settings)
        await seat.pre_game(ctx)

    async def play(self, ctx: TeamContext) -> None:
        try:
            await self.seat.play(ctx)
        finally:  # (the match records the iterations at the whistle, before the post-game)
            acted = [c.get("arguments", {}).get("player") for c in self.seat.calls if "tick_start" in c]
            self.iterations = [acted.count(name) for name in self.seat.players]  # the paper's I: actions

    async def post_game(self, ctx: TeamContext) -> None:
        seat = self.seat
        self.problems.extend(seat.problems)
        seat.problems.clear()
        write_calls(ctx, seat)


def write_calls(ctx: TeamContext, seat: Seat) -> None:
    """The episode's tool calls, one JSON line each (the team's artefact `tools.jsonl`), and the clock they
    played on."""
    ctx.out_dir.mkdir(parents=True, exist_ok=True)
    lines = [json.dumps({"clock": ctx.clock.mode, "window_s": seat.window_s})]
    lines += [json.dumps(c, default=str) for c in seat.take_calls()]
    (ctx.out_dir / "tools.jsonl").write_text("\n".join(lines) + "\n")
