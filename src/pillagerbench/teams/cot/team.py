"""The Chain-of-Thought baseline (paper, Experiments): once per episode, in the pre-game, one LLM
call writes every player's program from the scenario, the primitives' documentation, the team,
what the players see, and last episode's code, errors and chat (and, beside a person, what the person
said: people_said.txt, docs/people.md). During the game each player runs
its program, started again whenever it ends or throws, until the whistle.

An answer that cannot be used (no code, too few blocks, syntax errors, calls to primitives the
scenario lacks, no entry point) is sent back to the LLM with the problems, up to `attempts` calls;
after that, every player without a usable program does nothing this episode. With protocol=upstream
(the paper's loop) the answer is never sent back and a program is started at most
UPSTREAM_STEPS times, as upstream's 10 steps. Everything (prompt,
answers, programs, problems, iterations) goes to `<team out_dir>/cot.json`.
"""

from __future__ import annotations

import asyncio
import json
import time
from pathlib import Path
from typing import Any

from pydantic import Field

from pillagerbench.agents import context as C
from pillagerbench.agents.code import ProgramsResult, programs_from_answer
from pillagerbench.agents.prompts import load_prompts
from pillagerbench.llm import LLMError
from pillagerbench.players import primitives as prim
from pillagerbench.scenarios.upstream import UPSTREAM_ATTEMPTS, UPSTREAM_STEPS
from pillagerbench.teams.base import Team, TeamContext
from pillagerbench.teams.heard import people_said
from pillagerbench.teams.options import TeamOptions

PROMPTS = load_prompts(Path(__file__).parent)
ROLE = "cot"


def task_text(ctx: TeamContext) -> str:
    return (
        f"Win the game for {ctx.side.team_name}: end with more points than {ctx.opponent.team_name}, "
        "starting now and for as long as the game lasts."
    )


class CoTOptions(TeamOptions):
    """cot's options (`red.KEY=VALUE`; conf/team/cot.yaml repeats them)."""

    attempts: int = Field(
        default=3,
        ge=1,
        description="LLM calls per episode when an answer cannot be used (each retry shows the problems)",
    )
    temperature: float | None = Field(default=None, ge=0, le=2, description="null = the llm preset's temperature")
    max_tokens: int | None = Field(
        default=4096,
        ge=1,
        description="answer cap; the presets' 512 is too short for two programs (null = the llm preset's)",
    )
    restart_pause_s: float = Field(
        default=1.0, ge=0, description="wait before restarting a program that ended within this many seconds"
    )
    max_chat_lines: int = Field(
        default=80, ge=0, description="last round's chat log shown to the LLM (after compressing repeats)"
    )


class ChainOfThought(Team):
    name = "cot"
    uses_llm = True
    Options = CoTOptions

    def __init__(self, **options: object):
        super().__init__(**options)
        o = CoTOptions.model_validate(options)
        self.attempts = o.attempts
        self.temperature, self.max_tokens = o.temperature, o.max_tokens
        self.restart_pause_s = o.restart_pause_s
        self.max_chat_lines = o.max_chat_lines
        self.programs: list = []
        self.last_code: dict[str, str | None] = {}  # the block each player got last episode
        self.last_problems: list[str] = []  # why last episode's code was not (all) used
        self.record: dict[str, Any] = {}

    # --- prompt -----------------------------------------------------------------------------

    def messages(self, ctx: TeamContext) -> list[dict]:
        players = ctx.side.player_names
        docs = prim.docs([*ctx.scenario.primitives, "mineflayer"])
        code_format = "\n".join(PROMPTS["code_format"].render(player=p) for p in players)
        system = PROMPTS["system"].render(primitives=docs, code_format=code_format)
        user = PROMPTS["user"].render(
            last_code=self._last_code_text(players),
            last_errors=self._last_errors_text(ctx),
            last_chat=self._last_chat_text(ctx),
            nearby_blocks=self._per_player(ctx, C.nearby_blocks),
            nearby_entities=self._per_player(ctx, C.nearby_entities),
            team_name=ctx.side.team_name,
            team_players=", ".join(players),
            scenario=ctx.scenario.description(),
            task=task_text(ctx),
            people_said=self._people_said_text(ctx),
        )
        return [{"role": "system", "content": system}, {"role": "user", "content": user}]

    def _per_player(self, ctx: TeamContext, fn) -> str:
        return "\n".join(
            f"{name} (at {C.position_text(obs)}): {fn(obs)}"
            for name in ctx.side.player_names
            for obs in [C.last_observation(ctx.observations.get(name) or [])]
        )

    def _last_code_text(self, players: list[str]) -> str:
        if not self.last_code:
            return "No code yet: this is the first round."
        parts = []
        for name in players:
            code = self.last_code.get(name)
            parts.append(f"{name}:\n```javascript\n{code}\n```" if code else f"{name}: no code (the bot did nothing)")
        return "\n".join(parts)

    def _last_errors_text(self, ctx: TeamContext) -> str:
        lines = [f"Your code was not used: {p}" for p in self.last_problems]
        events = C.episode_events(ctx.last_episode, ctx.side.player_names)
        for name, evs in events.items():
            errs = C.error_lines(evs)
            if errs:
                lines.append(f"{name}:\n" + "\n".join(errs[:10]))
        return "\n".join(lines) or C.NONE

    def _last_chat_text(self, ctx: TeamContext) -> str:
        players = ctx.side.player_names
        events = C.episode_events(ctx.last_episode, players[:1])[players[0]] if players else []
        agents = [p.name for s in ctx.scenario.sides for p in s.players]
        return C.chat_log_text(events, agents, max_lines=self.max_chat_lines)

    def _people_said_text(self, ctx: TeamContext) -> str:
        """What the side's people said in chat last round (everything since this team's last prompt, asked
        before that round's game): the section people_said.txt, or nothing when none of them spoke."""
        chat = ctx.last_episode.get("chat") or []
        return people_said(PROMPTS["people_said"], chat, ctx.people, max_lines=self.max_chat_lines)

    # --- phases -----------------------------------------------------------------------------

    async def pre_game(self, ctx: TeamContext) -> None:
        players = ctx.side.player_names
        self.programs = [None] * len(players)
        self.iterations = [0] * len(players)
        messages = self.messages(ctx)
        rec: dict[str, Any] = {
            "episode": ctx.episode,
            "team": ctx.side.team_name,
            "players": players,
            "protocol": ctx.protocol,
            "messages": messages,
            "attempts": [],
            "programs": {},
            "failures": {},
            "status": "ok",
        }
        self.record = rec
        best: ProgramsResult | None = None
        if ctx.llm is None:
            rec["status"], rec["error"] = "failed", "no LLM client (the match gave this team none)"
        else:
            best = await self._ask(ctx, messages, rec)
        self._take_programs(players, best, rec)
        self._write(ctx)

    async def _ask(self, ctx: TeamContext, messages: list[dict], rec: dict[str, Any]) -> ProgramsResult | None:
        """Asks for every player's code, retrying with the problems while some player has none;
        each attempt goes into `rec`. Returns the answer with the most usable programs."""
        assert ctx.llm is not None
        players = ctx.side.player_names
        kw: dict[str, Any] = {}
        if self.temperature is not None:
            kw["temperature"] = float(self.temperature)
        if self.max_tokens is not None:
            kw["max_tokens"] = int(self.max_tokens)
        attempts = UPSTREAM_ATTEMPTS if ctx.upstream_protocol else self.attempts
        best: ProgramsResult | None = None
        for attempt in range(attempts):
            t0 = time.monotonic()
            try:
                answer = await ctx.llm.complete(messages, role=ROLE, **kw)
            except LLMError as exc:
                rec["attempts"].append(
                    {"error": f"{type(exc).__name__}: {exc}", "latency_s": round(time.monotonic() - t0, 3)}
                )
                rec["error"] = f"{type(exc).__name__}: {exc}"
                break
            # ours re-asks on code that does nothing (the answer format's empty `main`), as tacticrafter does;
            # upstream's took any code
            result = programs_from_answer(
                answer.text, players, ctx.scenario.primitives, reject_idle=not ctx.upstream_protocol
            )
            problems = list(result.problems)
            if answer.truncated:
                problems.insert(0, "the answer was cut off (too long): be shorter")
            rec["attempts"].append(
                {
                    "answer": answer.text,
                    "finish_reason": answer.finish_reason,
                    "latency_s": answer.latency_s,
                    "output_tokens": answer.output_tokens,
                    "problems": problems,
                }
            )
            if best is None or result.usable >= best.usable:
                best = result
            if result.complete:
                break
            if attempt + 1 < attempts:
                messages = messages + [
                    {"role": "assistant", "content": answer.text},
                    {
                        "role": "user",
                        "content": PROMPTS["retry"].render(
                            problems="\n".join(f"- {p}" for p in problems), players=", ".join(players)
                        ),
                    },
                ]
                rec["messages"] = messages
        return best

    def _take_programs(self, players: list[str], best: ProgramsResult | None, rec: dict[str, Any]) -> None:
        """Each player's program from the best answer (or why it has none), the record's status, and
        what the next episode's prompt shows of this one."""
        for k, name in enumerate(players):
            program = best.programs[k] if best else None
            self.programs[k] = program
            if program is not None:
                rec["programs"][name] = program.to_dict()
            else:
                reasons = [p for p in (best.problems if best else []) if p.startswith(f"{name}:")] or (
                    best.problems if best and best.problems else [rec.get("error") or "no usable answer"]
                )
                rec["failures"][name] = "; ".join(reasons)
        if rec["failures"] and rec["status"] == "ok":
            rec["status"] = "failed" if len(rec["failures"]) == len(players) else "partial"
        self.last_code = {
            name: (best.blocks[k] if best and k < len(best.blocks) else None) for k, name in enumerate(players)
        }
        self.last_problems = [
            f"{name}: {why}" if not why.startswith(f"{name}:") else why for name, why in rec["failures"].items()
        ]

    async def play(self, ctx: TeamContext) -> None:
        players = ctx.side.player_names
        self.iterations = [0] * len(players)
        await asyncio.gather(*(self._keep_running(ctx, k, ctx.players[name]) for k, name in enumerate(players)))

    async def _keep_running(self, ctx: TeamContext, k: int, player) -> None:
        program = self.programs[k] if k < len(self.programs) else None
        if program is None:  # the fallback: this player does nothing this episode
            await ctx.sleep(ctx.time_left(), player.name)
            return
        while ctx.time_left() > 0:
            if ctx.upstream_protocol and self.iterations[k] >= UPSTREAM_STEPS:
                await ctx.sleep(ctx.time_left(), player.name)  # upstream: no 11th step
                return
            self.iterations[k] += 1
            started, failed = ctx.clock.now(), False
            try:
                await player.run(program.exec_code)  # the match stops it at the whistle
            except Exception as exc:  # noqa: BLE001 - the bot cannot run code right now: note it and try again
                failed = True
                self.record.setdefault("run_errors", []).append(
                    f"{ctx.side.player_names[k]}: {type(exc).__name__}: {exc}"
                )
            await ctx.pause_before_rerun(player.name, self.restart_pause_s, started, failed)

    async def post_game(self, ctx: TeamContext) -> None:
        players = ctx.side.player_names
        self.record["iterations"] = dict(zip(players, self.iterations))
        events = C.episode_events(ctx.last_episode, players)
        self.record["errors"] = {name: C.error_lines(evs)[:20] for name, evs in events.items()}
        self._write(ctx)

    def _write(self, ctx: TeamContext) -> None:
        ctx.out_dir.mkdir(parents=True, exist_ok=True)
        (ctx.out_dir / "cot.json").write_text(json.dumps(self.record, indent=1, default=str))

    # --- checkpoint ---------------------------------------------------------------------------

    def state(self) -> dict[str, Any]:
        return {"last_code": self.last_code, "last_problems": self.last_problems}

    def load_state(self, state: dict[str, Any]) -> None:
        self.last_code = dict(state.get("last_code") or {})
        self.last_problems = list(state.get("last_problems") or [])
