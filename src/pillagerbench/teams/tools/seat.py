"""A seat at a team: where an agent outside the team's own code (an MCP client, an Inspect agent, our
`tools` team's model) sits, its tool calls becoming its players' actions under the same rules as code.

The seat lives for a whole run; the team sitting in it (`AgentTeam`, or the `tools` team) opens each
episode's pre-game (`pre_game`) and game (`play`) on it. Phases, as `status` says them: `pre_game`
(from the run's start, and again after each whistle, until the next game begins), `play`, `over`
(after the last episode, or once the agent has left). An episode's pre-game ends at the agent's first
acting call, or after `pregame_timeout_s`; an acting call made in the pre-game waits for the game and
starts on its first tick.

Game time: `world_hold.py` (on the lockstep clock the world waits while the agent thinks). An agent that
neither acts nor calls for `think_limit_s` of wall time lets the world go on without it (a problem of the
team's, on its record).
"""

from __future__ import annotations

import asyncio
import json
import time
from collections.abc import Callable
from typing import Any

import jsonschema
from pydantic import Field

from pillagerbench.config.sides import SIDES
from pillagerbench.players import events as ev
from pillagerbench.scenarios import Scenario
from pillagerbench.server.clock import TICK_S
from pillagerbench.teams.base import TeamContext
from pillagerbench.teams.options import TeamOptions
from pillagerbench.teams.tools.spec import ToolResult, ToolSpec
from pillagerbench.teams.tools.surface import RETURNED, call_code, primitives_of, tools_of
from pillagerbench.teams.tools.world_hold import WorldHold

PHASES = ("pre_game", "play", "over")


class SeatOptions(TeamOptions):
    """The options of a team that sits in a seat (`agent`, `tools`): its game time's limits."""

    pregame_timeout_s: float = Field(default=60.0, gt=0, description="the pre-game ends without an acting call")
    window_ms: float = Field(default=50.0, ge=0, description="lockstep: acting calls this close start on one tick")
    think_limit_s: float = Field(default=300.0, gt=0, description="lockstep: the world waits this long at most")


class Refused(Exception):
    """A tool call that cannot be taken; the message names the problem (a tool error, the game goes on)."""


class Seat:
    def __init__(
        self,
        scenario: Scenario,
        side: str,
        *,
        pregame_timeout_s: float = 60.0,
        window_s: float = 0.05,
        think_limit_s: float = 300.0,
    ):
        self.scenario, self.side = scenario, side
        self.players = list(scenario.side(side).player_names)
        self.specs = {t.name: t for t in tools_of(scenario, side)}
        self._checks = {n: jsonschema.Draft202012Validator(t.parameters) for n, t in self.specs.items()}
        self._primitives = {p.name: p for p in primitives_of(list(scenario.primitives))}
        self.pregame_timeout_s, self.think_limit_s = pregame_timeout_s, think_limit_s
        self.phase, self.episode = "pre_game", 0
        self.ctx: TeamContext | None = None
        # the calls since the last episode's were written (`take_calls`): the next episode's, made from its
        # pre-game on, or before it (the team's artefact tools.jsonl)
        self.calls: list[dict[str, Any]] = []
        self._unlogged: list[tuple[Any, str, str]] = []  # refusals before an episode's event log was open
        self.problems: list[str] = []
        self.left = False  # the agent has gone (a client that disconnected)
        self._ready = asyncio.Event()  # an episode's context is here (pre-game begun)
        self._acted = asyncio.Event()  # the pre-game's first acting call
        self._game = asyncio.Event()  # the game is on
        self._changed = asyncio.Event()  # any change of phase (wakes those waiting for one)
        self.world = WorldHold(side, self.players, window_s)  # the world's holds while the agent plays
        self._letting_go: asyncio.Task | None = None  # the world going on without an agent that left
        self._t0 = self._last_call = time.monotonic()  # (the last call's start or end)

    def configure(self, options: SeatOptions) -> None:
        """The limits of the team sitting here."""
        self.pregame_timeout_s, self.think_limit_s = options.pregame_timeout_s, options.think_limit_s
        self.world.window_s = options.window_ms / 1000

    @property
    def window_s(self) -> float:
        """Acting calls arriving this close (wall time) while the world is held start on one tick."""
        return self.world.window_s

    @property
    def tools(self) -> list[ToolSpec]:
        return list(self.specs.values())

    # --- the team's side: the episode's phases --------------------------------------------------------
    async def pre_game(self, ctx: TeamContext) -> None:
        """An episode's pre-game: its context is the agent's until the whistle; returns at the agent's first
        acting call (or after pregame_timeout_s, or at once once the agent has left)."""
        self.ctx, self.episode = ctx, ctx.episode
        self._acted.clear()
        self._ready.set()
        self._set_phase("pre_game")
        for player, tool, message in self._unlogged:  # refused before the episode's log was open
            self._note_refusal(player, tool, message)
        self._unlogged.clear()
        if self.left:
            return
        try:
            await asyncio.wait_for(self._acted.wait(), self.pregame_timeout_s)
        except asyncio.TimeoutError:
            self.problems.append(f"no acting call within pregame_timeout_s={self.pregame_timeout_s:g}: the game began")

    async def play(self, ctx: TeamContext) -> None:
        """The game: the agent's calls act until the whistle cancels this."""
        if self.left:
            await ctx.clock.rest(self.players, ctx.time_left())
            return
        await self.world.start(ctx)
        self._set_phase("play")
        self._game.set()
        watcher = asyncio.create_task(self._watch_thinking(ctx))
        try:
            await asyncio.Event().wait()  # the whistle cancels the team's play
        finally:
            watcher.cancel()
            self._game.clear()
            self._ready.clear()
            await self.world.stop()
            self._set_phase("pre_game")

    def finish(self) -> None:
        """The run is over: every call from now on is told so."""
        self._set_phase("over")

    def leave(self) -> None:
        """The agent has gone: its players do nothing for the rest of the episode (the world goes on)."""
        if not self.left:
            self.left = True
            self.problems.append("the agent left: its players did nothing for the rest of the episode")
            self._acted.set()
            if self._game.is_set() and self.ctx is not None:
                self._letting_go = asyncio.get_running_loop().create_task(self.world.let_go(self.ctx))

    def _set_phase(self, phase: str) -> None:
        self.phase = phase
        self._changed.set()
        self._changed = asyncio.Event()

    # --- the agent's side: one tool call ------------------------------------------------------------
    async def call(self, name: str, arguments: dict[str, Any] | None = None) -> ToolResult:
        """One tool call: its result, or a tool error naming the problem (never an exception)."""
        await asyncio.sleep(0)  # every call lets the match's own tasks run (a tight loop of calls cannot starve it)
        t0 = self._last_call = time.monotonic()
        args = dict(arguments or {})
        entry: dict[str, Any] = {"tool": name, "arguments": args, "at_s": round(t0 - self._t0, 3)}
        try:
            data = await self._dispatch(name, args, entry)
            result = ToolResult(json.dumps(data, default=str), data=data)
        except Refused as exc:
            entry["refused"] = str(exc)
            self._note_refusal(args.get("player"), name, str(exc))
            result = ToolResult(str(exc), error=True)
        self._last_call = time.monotonic()
        entry["wall_s"] = round(self._last_call - t0, 4)
        self.calls.append(entry)
        return result

    def _check(self, name: str, args: dict[str, Any]) -> ToolSpec:
        spec = self.specs.get(name)
        if spec is None:
            raise Refused(f"unknown tool {name!r}; the tools: {', '.join(self.specs)}")
        player = args.get("player")
        if "player" in spec.parameters["properties"] and player is not None and player not in self.players:
            raise Refused(
                f"{name}: player {player!r} is not on the {self.side} team (its players: {', '.join(self.players)})"
            )
        problem = next(iter(sorted(self._checks[name].iter_errors(args), key=lambda e: e.path)), None)
        if problem is not None:
            where = ".".join(map(str, problem.path))
            raise Refused(f"{name}: bad arguments: {where + ': ' if where else ''}{problem.message}")
        return spec

    async def _dispatch(self, name: str, args: dict[str, Any], entry: dict[str, Any]) -> dict[str, Any]:
        spec = self._check(name, args)
        if name == "status":
            return self.status()
        if self.phase == "over":
            raise Refused(f"{name}: the run is over (status says so); nothing more can be done")
        if not spec.acting:
            return await self._observe(args["player"])
        return await self._act(name, args, entry)

    def status(self) -> dict[str, Any]:
        ctx = self.ctx
        playing = self.phase == "play" and ctx is not None
        return {
            "phase": self.phase,
            "episode": self.episode,
            "players": self.players,
            "time_left_s": round(ctx.time_left(), 2) if playing and ctx is not None else None,
            "scores": {k: (ctx.scores.get(k, 0) if ctx else 0) for k in SIDES},
        }

    async def _context(self) -> TeamContext:
        while True:
            if self.phase == "over":
                raise Refused("the run is over (status says so); nothing more can be done")
            if self._ready.is_set() and self.ctx is not None:
                return self.ctx
            await self._changed.wait()

    async def _observe(self, player: str) -> dict[str, Any]:
        ctx = await self._context()
        events = await ctx.players[player].observe()
        return {"player": player, "observation": ev.last_observation(events)}

    # --- acting -------------------------------------------------------------------------------------
    async def _act(self, name: str, args: dict[str, Any], entry: dict[str, Any]) -> dict[str, Any]:
        ctx = await self._game_on()
        entry["episode"], entry["tick_start"] = ctx.episode, _tick(ctx)
        async with self.world.acting(ctx, [args["player"]], again=not self.left):
            result = await self._perform(ctx, name, args)
        entry["tick_end"] = min(_tick(ctx), round(ctx.episode_length / TICK_S))  # (the whistle's, at most)
        if ctx.time_left() <= 0:
            result["ended"] = "the episode ended (the whistle) while this call was in flight"
        return result

    async def _game_on(self) -> TeamContext:
        """The context of a game in play, waited for: an acting call in a pre-game ends it and starts on the
        game's first tick; one made after a whistle waits for the next game."""
        while True:
            if self.phase == "over":
                raise Refused("the run is over (status says so); nothing more can be done")
            ctx = self.ctx
            if self._game.is_set() and ctx is not None and ctx.time_left() > 0:
                return ctx
            if self._ready.is_set() and not self._game.is_set():
                self._acted.set()  # the pre-game ends at the first acting call
            await self._changed.wait()

    async def _perform(self, ctx: TeamContext, name: str, args: dict[str, Any]) -> dict[str, Any]:
        player = args["player"]
        handle = ctx.players[player]
        if name == "wait":
            await ctx.sleep(args["ticks"] * TICK_S, player=player)
            return {"player": player, "waited_ticks": args["ticks"]}
        if name == "run_code":
            ticks = args.get("max_ticks")
            events = await handle.run(args["code"], timeout=ticks * TICK_S if ticks else None)
        elif name == "chat":
            events = await handle.run(f"chat({json.dumps(args['text'])})")
        else:
            code = call_code(self._primitives[name], {k: v for k, v in args.items() if k != "player"})
            events = await handle.run(code)
        return _outcome(player, events)

    async def charge(self, tokens: int) -> None:
        """Thinking charged in game time (`clock.ticks_per_1k_tokens`: the LLM client's charge after each of a
        seated team's model calls): every player waits it out as one acting call, the world running (the
        clock's own charge rests them while the team holds the world, which would then never go on)."""
        ctx = self.ctx
        if ctx is None or not self._game.is_set():
            return
        async with self.world.acting(ctx, self.players, again=not self.left):
            await ctx.clock.charge(tokens, self.players)

    async def _watch_thinking(self, ctx: TeamContext) -> None:
        """An agent that neither acts nor answers for think_limit_s of wall time: the world goes on."""
        while True:
            await asyncio.sleep(min(1.0, self.think_limit_s))
            quiet = time.monotonic() - self._last_call
            if self.world.thinking and quiet > self.think_limit_s:
                self.problems.append(
                    f"no call for think_limit_s={self.think_limit_s:g} s of wall time: the world went on"
                )
                await self.world.let_go(ctx)
                return

    def _note_refusal(self, player: Any, tool: str, message: str) -> None:
        ctx = self.ctx  # (an episode's event log is open from its pre-game to its whistle)
        if ctx is None or not self._ready.is_set():
            self._unlogged.append((player, tool, message))
        elif isinstance(player, str) and player in ctx.players:
            note: Callable[[list], None] | None = getattr(ctx.players[player], "note", None)
            if note is not None:
                note(["onToolRefused", {"onToolRefused": message, "tool": tool}])

    def take_calls(self) -> list[dict[str, Any]]:
        """The calls since the last take (an episode's, written in its post-game), forgotten here."""
        calls, self.calls = self.calls, []
        return calls


def _tick(ctx: TeamContext) -> int:
    """The game's tick now, counted from its first (on the real clock, wall time in ticks)."""
    start = (ctx.deadline or 0.0) - ctx.episode_length
    return round((ctx.clock.now() - start) / TICK_S)


def _outcome(player: str, events: list) -> dict[str, Any]:
    """A run's events as the agent reads them: each event's own message, what a primitive returned, the
    final observation."""
    returned: list[Any] = []
    shown: list[list] = []
    for kind, message in ((e[0], e[1].get(e[0])) for e in events if e and e[0] != "observe"):
        if kind == "onSave" and isinstance(message, str) and message.startswith(RETURNED):
            returned.append(json.loads(message.removeprefix(RETURNED)))
        else:
            shown.append([kind, message])
    out: dict[str, Any] = {"player": player, "events": shown, "observation": ev.last_observation(events)}
    if returned:
        out["returned"] = returned[-1]
    return out
