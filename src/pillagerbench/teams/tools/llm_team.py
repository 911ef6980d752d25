"""`tools` (beyond the paper): an LLM team that plays through function calling, with the same tools as an
outside agent (`surface.py`) from its own seat (`seat.py`), the scenario's facts (`briefing`) in its prompt.

Each episode one conversation: system (the briefing and how to play) and user (the episode, what each
player sees at its reset, last episode's score); then turns until the whistle: the model is asked with
the seat's tools (`role="action"`), the calls of one answer are made at once (one model turn: on the
lockstep clock they start on the same game tick) and their results go back as tool messages. The
pre-game ends at the model's first acting call. An answer without a tool call is nudged once; a second
in a row, an LLM error, or `max_turns` calls end the team's episode (its players idle to the whistle,
the reason in the episode's problems). A call whose arguments are not a JSON object, an unknown tool, a
player not on the team or bad arguments are tool errors the model reads; the game goes on.

The conversation stays bounded: the last `history_turns` turns are sent, and only the latest turn's
tool results keep their observations. Game time (docs/any-agent.md): on the lockstep clock the world
waits while the model thinks (the LLM client's thinking hold, and the seat's own between calls).
Artefacts: `<team out_dir>/tools.jsonl` (the seat's calls) and `transcript.json` (every message, every
answer's latency and tokens, the problems, the acting calls per player).
"""

from __future__ import annotations

import asyncio
import json
from typing import Any

from pydantic import Field

from pillagerbench.agents import context as C
from pillagerbench.llm import LLMError
from pillagerbench.llm.tool_calls import ToolAnswer, ToolCall, ask_with_tools, tool_result
from pillagerbench.teams.base import Team, TeamContext
from pillagerbench.teams.tools.agent import write_calls
from pillagerbench.teams.tools.seat import Seat, SeatOptions
from pillagerbench.teams.tools.surface import briefing

ROLE = "action"
STOP_GRACE_S = 1.0  # at the whistle: how long the calls in flight (their code stopped) may take to return
HOW_TO_PLAY = """How to play: each of your answers is one turn. Call tools in it: several at once if you like \
(e.g. one action for each player); the calls of one answer start together and run at the same time. An acting \
call returns when its action ends, with the run's events and the player's observation. Keep your players busy \
until the game ends: after every result, act again. `observe` shows what a player sees and holds, `status` the \
time left and the scores. The primitives (e.g. mineBlock) are single actions; run_code runs a longer program."""
NUDGE = "Act with the tools: call at least one of them (an answer without a tool call does nothing in the game)."
CUT = " Your last answer was cut off: be shorter."
DROPPED = "(observation dropped: see the latest results, or call observe)"


class ToolsOptions(SeatOptions):
    """tools' options (`red.KEY=VALUE`; conf/team/tools.yaml repeats them)."""

    temperature: float | None = Field(default=None, ge=0, le=2, description="null = the llm preset's temperature")
    max_tokens: int | None = Field(
        default=2048, ge=1, description="answer cap per model turn (a run_code program needs room; null = the preset's)"
    )
    max_turns: int = Field(
        default=200, ge=1, description="LLM calls per episode; after the last, the players idle to the whistle"
    )
    history_turns: int = Field(
        default=12, ge=1, description="model turns kept in the conversation (only the latest keeps observations)"
    )


class Conversation:
    """The messages sent: the opening (system, user) and the last `keep` turns (an assistant message and
    what answers it: tool results, a nudge), only the latest turn's tool results with observations."""

    def __init__(self, opening: list[dict[str, Any]], keep: int):
        self.opening, self.keep = opening, keep
        self.turns: list[list[dict[str, Any]]] = []  # each turn as sent while it is the latest
        self.short: list[list[dict[str, Any]]] = []  # each turn as sent once a newer one follows
        self.transcript: list[dict[str, Any]] = list(opening)  # every message, in full

    def add(self, turn: list[dict[str, Any]]) -> None:
        self.turns.append(turn)
        self.short.append([_without_observation(m) for m in turn])
        self.transcript.extend(turn)
        del self.turns[: -self.keep], self.short[: -self.keep]

    def messages(self) -> list[dict[str, Any]]:
        older = [m for turn in self.short[:-1] for m in turn]
        return [*self.opening, *older, *(self.turns[-1] if self.turns else [])]


def _without_observation(message: dict[str, Any]) -> dict[str, Any]:
    """A tool result without its observation (the observations of older turns are stale)."""
    if message.get("role") != "tool":
        return message
    try:
        data = json.loads(message["content"])
    except (ValueError, TypeError):
        return message
    if not isinstance(data, dict) or "observation" not in data:
        return message
    return {**message, "content": json.dumps({**data, "observation": DROPPED}, default=str)}


class ToolsTeam(Team):
    name = "tools"
    uses_llm = True
    Options = ToolsOptions

    def __init__(self, **options: object):
        super().__init__(**options)
        self.settings = ToolsOptions.model_validate(options)
        self.seat: Seat | None = None  # made at the first pre-game; one for the whole run
        self.conversation = Conversation([], self.settings.history_turns)
        self.record: dict[str, Any] = {}
        self._loop: asyncio.Task | None = None
        self._asking = False  # the loop waits for the model (cancelled at the whistle rather than waited for)
        self._over = False  # the whistle: the loop asks no more

    # --- phases ---------------------------------------------------------------------------------------
    async def pre_game(self, ctx: TeamContext) -> None:
        seat = self._seat_for(ctx)
        seat.left = False  # a new episode: the model sits again (after leaving the last one, see _converse)
        self.iterations = [0] * len(seat.players)
        self.conversation = Conversation(self.opening(ctx), self.settings.history_turns)
        self.record = {"episode": ctx.episode, "team": ctx.side.team_name, "players": seat.players, "asks": []}
        self._over, self._loop = False, None
        if ctx.llm is None:
            self.problems.append("no LLM client (the match gave this team none)")
            seat.leave()
        else:
            self._loop = asyncio.create_task(self._converse(ctx), name=f"tools-{ctx.side.key}")
        await seat.pre_game(ctx)  # returns at the model's first acting call (or when the loop has ended)

    async def play(self, ctx: TeamContext) -> None:
        if ctx.llm is not None and ctx.llm.thinking.charge is not None:  # lockstep: thinking charged in game time
            ctx.llm.thinking.charge = self._seat().charge  # as its players waiting, the world running
        try:
            await self._seat().play(ctx)
        finally:  # the whistle (the match cancels the play): the loop stops, its calls in flight return
            await self._stop_loop(STOP_GRACE_S)
            self.iterations = self._acting_calls()

    async def post_game(self, ctx: TeamContext) -> None:
        await self._stop_loop(0.0)
        seat = self._seat()
        self.iterations = self._acting_calls()
        refused = [f"{c['tool']}: {c['refused']}" for c in seat.calls if "refused" in c]
        bad = refused + list(self.record.get("malformed", []))
        if bad:
            self.problems.append(f"{len(bad)} tool call(s) refused or malformed; the first: {bad[0]}")
        self.problems.extend(seat.problems)
        seat.problems.clear()
        write_calls(ctx, seat)
        self.record.update(
            iterations=dict(zip(seat.players, self.iterations)),
            problems=list(self.problems),
            messages=self.conversation.transcript,
        )
        (ctx.out_dir / "transcript.json").write_text(json.dumps(self.record, indent=1, default=str))

    # --- the prompt -----------------------------------------------------------------------------------
    def opening(self, ctx: TeamContext) -> list[dict[str, Any]]:
        system = f"{briefing(ctx.scenario, ctx.side.key)}\n\n{HOW_TO_PLAY}"
        return [{"role": "system", "content": system}, {"role": "user", "content": self.episode_text(ctx)}]

    def episode_text(self, ctx: TeamContext) -> str:
        lines = [f"Episode {ctx.episode} is about to begin. What your players see now:"]
        for name in ctx.side.player_names:
            obs = C.last_observation(ctx.observations.get(name) or [])
            lines.append(
                f"- {name} at {C.position_text(obs)}; inventory: {C.inventory_text(obs)}; "
                f"nearby blocks: {C.nearby_blocks(obs)}; nearby entities: {C.nearby_entities(obs)}"
            )
        last = ctx.last_episode.get("record")
        if last is not None:
            own, other = ctx.side.key, ctx.opponent.key
            scores = {"red": last.red_score, "blue": last.blue_score}
            lines.append(f"Last episode: your team {scores[own]:g} points, the opponents {scores[other]:g}.")
        lines.append("The game begins with your first action: act with the tools.")
        return "\n".join(lines)

    # --- the loop -------------------------------------------------------------------------------------
    async def _converse(self, ctx: TeamContext) -> None:
        """The episode's turns until the whistle; when they end before it, the players idle (the seat left)."""
        try:
            why = await self._turns(ctx)
        except Exception as exc:  # noqa: BLE001 - a fault of the team's own: its episode, not the match, ends
            why = f"the team's loop failed: {type(exc).__name__}: {exc}"
        self.record["stopped"] = why or "the whistle"
        if why is not None and not self._over:
            self.problems.append(f"{why}: no more turns this episode")
            self._seat().leave()  # its players idle to the whistle (the seat says so in the problems)

    async def _turns(self, ctx: TeamContext) -> str | None:
        """Asks and calls until the whistle (None) or a reason to stop asking."""
        assert ctx.llm is not None
        seat, o = self._seat(), self.settings
        params: dict[str, Any] = {"temperature": o.temperature, "max_tokens": o.max_tokens}
        params = {k: v for k, v in params.items() if v is not None}
        unanswered = 0  # answers in a row without a tool call
        for _ in range(o.max_turns):
            if not self._playing(ctx):
                return None
            self._asking = True
            try:
                answer = await ask_with_tools(
                    ctx.llm, self.conversation.messages(), tools=seat.tools, role=ROLE, **params
                )
            except LLMError as exc:
                return f"LLM: {type(exc).__name__}: {exc}"
            finally:
                self._asking = False
            self._note(answer)
            if not self._playing(ctx):  # the whistle came while it thought: its calls would wait for the next game
                return None
            if answer.tool_calls:
                unanswered = 0
                results = await asyncio.gather(*(self._call(call) for call in answer.tool_calls))
                self.conversation.add([answer.assistant_message, *results])
                continue
            unanswered += 1
            if unanswered > 1:
                return "two answers in a row without a tool call"
            nudge = NUDGE + (CUT if answer.truncated else "")
            self.conversation.add([answer.assistant_message, {"role": "user", "content": nudge}])
        return f"max_turns={o.max_turns} LLM calls made"

    async def _call(self, call: ToolCall) -> dict[str, Any]:
        """One tool call made in the seat, as the tool message answering it (errors included)."""
        if call.arguments is None:
            text = (
                f"error: {call.name}: the arguments are not a JSON object ({call.raw_arguments[:200]!r}); "
                "nothing was done"
            )
            self.record.setdefault("malformed", []).append(text.removeprefix("error: "))
            return tool_result(call, text)
        result = await self._seat().call(call.name, call.arguments)
        return tool_result(call, f"error: {result.text}" if result.error else result.text)

    def _note(self, answer: ToolAnswer) -> None:
        self.record["asks"].append(
            {
                "latency_s": answer.latency_s,
                "finish_reason": answer.finish_reason,
                "input_tokens": answer.input_tokens,
                "output_tokens": answer.output_tokens,
                "cache_hit": answer.cache_hit,
                "calls": [call.name for call in answer.tool_calls],
            }
        )

    def _playing(self, ctx: TeamContext) -> bool:
        """This episode's pre-game or game, before its whistle."""
        seat = self._seat()
        return not self._over and seat.episode == ctx.episode and seat.phase != "over" and ctx.time_left() > 0

    async def _stop_loop(self, grace_s: float) -> None:
        """The loop asks no more; a call to the model is cancelled, the tool calls in flight get `grace_s`
        to return (their code is stopped at the whistle), then are cancelled."""
        self._over = True
        task = self._loop
        if task is None or task.done():
            return
        if self._asking:
            task.cancel()
        done, _ = await asyncio.wait([task], timeout=grace_s)
        if not done:
            task.cancel()
            await asyncio.wait([task], timeout=STOP_GRACE_S)

    # --- the seat -------------------------------------------------------------------------------------
    def _seat_for(self, ctx: TeamContext) -> Seat:
        if self.seat is None:
            self.seat = Seat(ctx.scenario, ctx.side.key)
            self.seat.configure(self.settings)
        return self.seat

    def _seat(self) -> Seat:
        if self.seat is None:
            raise RuntimeError("the tools team has no seat before its first pre-game")
        return self.seat

    def _acting_calls(self) -> list[int]:
        """The paper's I: this episode's acting calls per player."""
        seat = self._seat()
        acted = [c.get("arguments", {}).get("player") for c in seat.calls if "tick_start" in c]
        return [acted.count(name) for name in seat.players]
