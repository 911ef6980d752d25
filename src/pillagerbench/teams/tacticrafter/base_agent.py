"""A base agent (paper §Base Agents): one per player, all in parallel. Each iteration writes code
(the action role), runs it, then criticises the run (the critic role) and writes the next code
from the critique, until the iteration cap or the whistle.

- The first code of an episode is written in the pre-game (not timed), so iteration 1 starts at
  the whistle; later code is written during the game, while the bot waits.
- Every code run counts as one iteration (the paper's I), at most `iterations` per episode; after
  the cap the last good code is run again without LLM calls (`reruns`, not counted).
- Code is good when it parsed and its run did not fail at once (an error within `quick_fail_s`).
  When a new answer has no usable code after its retries, or the LLM fails, the agent runs its
  last good code (or, if it has none, the code it has unless that failed at once). After
  `max_llm_failures` failed code requests in an episode the agent stops asking.
- protocol=upstream (the paper's loop, TeamContext.protocol): no rerun after the cap (the player
  idles), no fallback code when an answer is unusable or the LLM fails (the iteration passes without
  a run and the agent asks again, as upstream's did), the action answer is never re-asked.
- No LLM call starts unless the time left exceeds both `min_llm_time_s` and the role's expected
  latency; a call still running at the whistle is abandoned. BudgetExceeded stops every LLM call
  of the team for the rest of the episode.
- Events of a run are deduplicated (reference §7.6) before they reach the critic or the action
  prompt; the counts before and after are kept.
"""

from __future__ import annotations

import time
from typing import Any, Protocol

from pillagerbench.agents import context as C
from pillagerbench.agents.asking import Asked, RoleLLM, ask
from pillagerbench.agents.code import CodeError, Program, check_program, extract_code_blocks, idle_problem
from pillagerbench.llm.parsing import parse_json
from pillagerbench.players import events as pev
from pillagerbench.players import primitives as prim
from pillagerbench.players.observation import Observation
from pillagerbench.scenarios.upstream import UPSTREAM_ATTEMPTS
from pillagerbench.teams.base import TeamContext
from pillagerbench.teams.heard import people_said

from .events import DedupStats, dedupe, last_observation, tail
from .memory import Memory
from .templates import PROMPTS

ACTION, CRITIC = "action", "critic"


class AgentsTeam(Protocol):
    """What a base agent reads from its team (TactiCrafter, team.py, is the one implementation)."""

    agents: list[BaseAgent]
    agent_names: list[str]
    memory: Memory
    llm: RoleLLM | None
    llm_off: str | None
    attempts: int
    keep_messages: bool
    max_chat_lines: int
    max_iterations: int
    max_llm_failures: int
    min_llm_time_s: float
    quick_fail_s: float
    restart_pause_s: float

    def objective(self, ctx: TeamContext) -> str: ...

    def tactics_text(self) -> str: ...

    def expected_latency(self, role: str) -> float: ...

    def note_call(self, role: str, asked: Asked) -> None: ...


def parse_code(text: str, allowed) -> Program:
    """The program in an action answer: its ```javascript blocks joined, checked with acorn."""
    blocks = extract_code_blocks(text)
    if not blocks:
        raise ValueError("the answer has no ```javascript code block")
    try:
        program = check_program("\n\n".join(blocks), allowed)
    except CodeError as exc:
        raise ValueError(str(exc)) from None
    idle = idle_problem(program)
    if idle is not None:
        raise ValueError(idle)
    return program


def parse_critique(text: str) -> dict:
    try:
        value = parse_json(text)
    except ValueError as exc:
        raise ValueError(f"no valid JSON in the answer ({exc})") from None
    if not isinstance(value, dict):
        raise ValueError('the answer must be one JSON object {"reasoning": ..., "success": ..., "critique": ...}')
    success = value.get("success")
    if isinstance(success, str) and success.lower() in ("true", "false"):
        success = success.lower() == "true"
    if not isinstance(success, bool):
        raise ValueError('"success" must be true or false')
    critique = value.get("critique")
    if critique is not None and not isinstance(critique, str):
        critique = str(critique)
    return {"reasoning": str(value.get("reasoning") or ""), "success": success, "critique": critique or ""}


class BaseAgent:
    def __init__(self, team: AgentsTeam, name: str, index: int):
        self.team, self.name, self.k = team, name, index
        self.program: Program | None = None  # what runs next
        self.good: Program | None = None  # last code whose run did not fail at once
        self.last_source: str | None = None  # the code of the last iteration, as written
        self.last_error: str = C.NONE
        self.critique: str | None = None
        self.success: bool | None = None
        self.events: list[list] = []  # the last run's events, deduplicated
        self.observation: Observation = {}
        self.chat_before: str = C.NONE  # chat shown before the first run (last episode's)
        self.stats = DedupStats()
        self.reruns = 0
        self.iterations = 0  # code runs counted this game (the paper's I); the team reads them, never writes
        self.record: dict[str, Any] = {}

    # --- episode start ---------------------------------------------------------------------------

    def start_episode(self, ctx, memory_code: dict[str, Any], chat_before: str) -> None:
        self.program, self.events, self.stats, self.reruns = None, [], DedupStats(), 0
        self.observation = last_observation(ctx.observations.get(self.name) or [])
        self.last_source = memory_code.get("code")
        self.critique = memory_code.get("critique")
        self.success = memory_code.get("success")
        self.last_error = memory_code.get("error") or C.NONE
        self.chat_before = chat_before
        self.good = None
        if self.last_source:  # last episode's code is the fallback until new code runs well
            try:
                self.good = check_program(self.last_source, ctx.scenario.primitives)
            except CodeError:
                self.good = None
        self.record = {"player": self.name, "calls": [], "iterations": [], "reruns": 0}

    # --- prompts ---------------------------------------------------------------------------------

    def _teammates_text(self) -> str:
        out = [
            f"{a.name}: {C.inventory_text(a.observation)} (at {C.position_text(a.observation)})"
            for a in self.team.agents
            if a is not self
        ]
        return "\n".join(out) or C.NONE

    def _inventory_text(self) -> str:
        used = (self.observation.get("status") or {}).get("inventoryUsed")
        return C.inventory_text(self.observation) + (f" ({used}/36 slots used)" if used is not None else "")

    def _chat_text(self) -> str:
        if not self.events:
            return self.chat_before
        return tail([str(x) for x in pev.chat_log(self.events)], self.team.max_chat_lines)

    def _people_said_text(self, ctx) -> str:
        """What the side's people said, from the chat the chat log shows (the last run's, or before the
        first run last episode's): prompts/people_said.txt, or nothing when none of them spoke."""
        heard = [str(x) for x in pev.chat_log(self.events)] if self.events else ctx.last_episode.get("chat") or []
        return people_said(PROMPTS["people_said"], heard, ctx.people, max_lines=self.team.max_chat_lines)

    def action_messages(self, ctx) -> list[dict]:
        t = self.team
        # the system prompt is the same for every player (a shared prefix: provider prompt caches)
        system = PROMPTS["action_system"].render(primitives=prim.docs([*ctx.scenario.primitives, "mineflayer"]))
        user = PROMPTS["action_user"].render(
            tactics=t.tactics_text(),
            previous_tactics=t.memory.previous_tactics or C.NONE,
            last_code=f"```javascript\n{self.last_source}\n```" if self.last_source else "No code yet.",
            execution_error=self.last_error or C.NONE,
            critique=self.critique or C.NONE,
            chat_log=self._chat_text(),
            status=C.status_text(self.observation),
            inventory=self._inventory_text(),
            teammates=self._teammates_text(),
            nearby_blocks=C.nearby_blocks(self.observation),
            nearby_entities=C.nearby_entities(self.observation),
            chests=C.chests_text(self.observation),
            username=self.name,
            team=f"{ctx.side.team_name} ({', '.join(ctx.side.player_names)})",
            scenario=ctx.scenario.description(),
            task=t.objective(ctx),
            people_said=self._people_said_text(ctx),
        )
        return [{"role": "system", "content": system}, {"role": "user", "content": user}]

    def critic_messages(self, ctx) -> list[dict]:
        t = self.team
        user = PROMPTS["critic_user"].render(
            execution_error=self.last_error or C.NONE,
            chat_log=self._chat_text(),
            status=C.status_text(self.observation),
            inventory=self._inventory_text(),
            teammates=self._teammates_text(),
            chests=C.chests_text(self.observation),
            username=self.name,
            task=t.objective(ctx),
            scenario=ctx.scenario.description(),
            tactics=t.tactics_text(),
        )
        return [{"role": "system", "content": PROMPTS["critic_system"].render()}, {"role": "user", "content": user}]

    # --- LLM calls ---------------------------------------------------------------------------------

    def can_call(self, ctx, role: str) -> bool:
        t = self.team
        if t.llm_off:
            return False
        left = ctx.time_left()
        return left == float("inf") or left > max(t.min_llm_time_s, 1.2 * t.expected_latency(role))

    def _note(self, role: str, asked: Asked, started: float, ctx) -> None:
        t = self.team
        t.note_call(role, asked)
        rec = {
            "role": role,
            "ok": asked.ok,
            "error": asked.error,
            "attempts": asked.attempts,
            "game_time_s": None if ctx.deadline is None else round(ctx.episode_length - ctx.time_left(), 2),
            "wall_s": round(time.monotonic() - started, 3),
        }
        if t.keep_messages:
            rec["messages"] = asked.messages
        self.record["calls"].append(rec)

    async def write_code(self, ctx) -> Program | None:
        started = time.monotonic()
        asked = await ask(
            self.team.llm,
            self.action_messages(ctx),
            role=ACTION,
            parse=lambda a: parse_code(a.text, ctx.scenario.primitives),
            attempts=UPSTREAM_ATTEMPTS if ctx.upstream_protocol else self.team.attempts,
            deadline=ctx,
            retry=lambda p: PROMPTS["code_retry"].render(problem=p),
        )
        self._note(ACTION, asked, started, ctx)
        return asked.value

    async def criticize(self, ctx) -> None:
        started = time.monotonic()
        asked = await ask(
            self.team.llm,
            self.critic_messages(ctx),
            role=CRITIC,
            parse=lambda a: parse_critique(a.text),
            attempts=self.team.attempts,
            deadline=ctx,
            retry=lambda p: PROMPTS["json_retry"].render(problem=p),
        )
        self._note(CRITIC, asked, started, ctx)
        if asked.value is not None:
            self.success, self.critique = asked.value["success"], asked.value["critique"]
        else:
            self.success, self.critique = None, None

    # --- the game ----------------------------------------------------------------------------------

    async def pre_game(self, ctx) -> None:
        if self.team.llm is None or self.team.llm_off:
            return
        self.program = await self.write_code(ctx)

    async def play(self, ctx) -> None:
        """Run, criticise and rewrite the code until the whistle (upstream: until the iteration cap)."""
        player = ctx.players[self.name]
        program: Program | None = self.program
        failures = self.iterations = 0
        upstream = ctx.upstream_protocol
        while ctx.time_left() > 0:
            if program is None and not upstream:
                program = self.good
            if program is None:
                step = await self._without_program(ctx, failures, upstream)
            else:
                step = await self._iteration(ctx, player, program, failures, upstream)
            if step is None:
                break
            program, failures = step

    async def _without_program(self, ctx, failures: int, upstream: bool) -> tuple[Program | None, int] | None:
        """No code to run: ask for some while that is possible. Returns (program, failures), or None
        once the agent idles until the whistle."""
        t = self.team
        if upstream:  # an unusable answer: an iteration without a run, as upstream's
            if self.iterations >= t.max_iterations or not self.can_call(ctx, ACTION):
                await self._idle_until_whistle(ctx)
                return None
            self.iterations += 1
            self.record["iterations"].append({"n": self.iterations, "counted": True, "no_code": True})
            return (await self.write_code(ctx) if self.iterations < t.max_iterations else None), failures
        if failures < t.max_llm_failures and self.can_call(ctx, ACTION):
            program = await self.write_code(ctx)
            if program is None:
                failures += 1
                await ctx.sleep(t.restart_pause_s, self.name)
            return program, failures
        await self._idle_until_whistle(ctx)
        return None

    async def _iteration(
        self, ctx, player, program: Program, failures: int, upstream: bool
    ) -> tuple[Program | None, int] | None:
        """One iteration: run the program, then criticise and rewrite it (or rerun the last good code).
        Returns (the next program, failures), or None at the whistle."""
        t = self.team
        it, duration, failed_at_once, counted = await self._run(ctx, player, program)
        if ctx.time_left() <= 0:
            it["ended_by_whistle"] = True
            return None
        fallback = self.good or (None if failed_at_once else program)
        if upstream and (self.iterations >= t.max_iterations or not self.can_call(ctx, CRITIC)):
            await self._idle_until_whistle(ctx)  # upstream: no more steps after the cap (nor once no call can finish)
            return None
        if (
            not counted
            or self.iterations >= t.max_iterations
            or failures >= t.max_llm_failures
            or not self.can_call(ctx, CRITIC)
        ):
            if duration < t.restart_pause_s:
                await ctx.sleep(t.restart_pause_s - duration, self.name)
            return fallback, failures
        await self.criticize(ctx)
        it["success"], it["critique"] = self.success, self.critique
        new = await self.write_code(ctx) if self.can_call(ctx, ACTION) else None
        if new is not None:
            return new, failures
        if duration < t.restart_pause_s:
            await ctx.sleep(t.restart_pause_s - duration, self.name)
        return (None if upstream else fallback), failures + 1

    async def _run(self, ctx, player, program: Program) -> tuple[dict[str, Any], float, bool, bool]:
        """Runs the program once (an iteration while under the cap, else a rerun) and records it.
        Returns (its iteration record, its duration, whether it failed at once, whether it counted)."""
        t = self.team
        counted = self.iterations < t.max_iterations
        if counted:
            self.iterations += 1
        else:
            self.reruns += 1
            self.record["reruns"] = self.reruns
        new_code = program.source != self.last_source
        self.last_source = program.source
        started = ctx.clock.now()
        events = await player.run(program.exec_code)
        duration = ctx.clock.now() - started
        deduped, stats = dedupe(events, t.agent_names)
        self.stats = self.stats.add(stats)
        self.events = deduped
        obs = last_observation(events)
        if obs:
            self.observation = obs
        errors = C.error_lines(events)
        failed_at_once = bool(errors) and duration < t.quick_fail_s
        self.last_error = "\n".join(errors[:5]) or C.NONE
        if not failed_at_once:
            self.good = program
        it = {
            "n": self.iterations,
            "counted": counted,
            "new_code": new_code,
            "entry": program.entry,
            "duration_s": round(duration, 2),
            "errors": errors[:3],
            "failed_at_once": failed_at_once,
            "events": stats.before,
            "events_deduped": stats.after,
        }
        self.record["iterations"].append(it)
        return it, duration, failed_at_once, counted

    async def _idle_until_whistle(self, ctx) -> None:
        self._idle(ctx)
        await ctx.sleep(ctx.time_left(), self.name)

    def _idle(self, ctx) -> None:
        self.record["idle_from_s"] = round(ctx.episode_length - ctx.time_left(), 2)

    def summary(self) -> dict[str, Any]:
        """What the team keeps of this agent (memory's code.json entry)."""
        good = self.good
        return {
            "code": good.source if good else self.last_source,
            "critique": self.critique,
            "success": self.success,
            "error": self.last_error if self.last_error != C.NONE else None,
        }
