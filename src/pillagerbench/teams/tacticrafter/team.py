"""TactiCrafter (paper §Methodology): the tactics module, the causal model, the opponent model and
one base agent per player, learning across the episodes of a series.

Per episode:
- pre-game (not timed): the causal model makes its first graph, or adds what last episode's chat
  and inventories show; from the second episode the opponent model guesses the opponent's
  tactics from its chat; the tactics module writes the team's tactics (first episode, unless
  preset) or updates them from last episode's events; each base agent writes its first code.
- game: the base agents run, criticise and rewrite their code in parallel (base_agent.py).
- post-game: every player's events are deduplicated and kept as a digest; the tactics, opponent
  tactics, causal graph and last good code are written to the team's episode directory
  (memory.py) with `tacticrafter.json` (every LLM call, iteration and deduplication count).

Whatever an LLM gets wrong (no tags, bad JSON, no code, an error, a timeout, the budget) is
recorded and the team goes on with what it has: last good tactics, graph, code.
"""

from __future__ import annotations

import asyncio
import json
import time
from pathlib import Path
from typing import Any

from pydantic import Field, field_validator

from pillagerbench.agents import context as C
from pillagerbench.agents.asking import Asked, RoleLLM, role_settings
from pillagerbench.rundir import has_team_state
from pillagerbench.teams.base import Team, TeamContext
from pillagerbench.teams.options import TeamOptions

from . import causal, opponent, tactics
from .base_agent import BaseAgent
from .calls import CallStats
from .events import (
    agent_names,
    chat_lines,
    digest_episode,
    inventories_text,
    longest_chat,
    nearby_blocks_text,
    opponent_chat,
    own_chat_with_inventory,
    tail,
)
from .memory import Memory
from .opponent import UNKNOWN

ROLES = ("tactics", "causal", "opponent", "action", "critic")


class TactiCrafterOptions(TeamOptions):
    """tacticrafter's options (`red.KEY=VALUE`; conf/team/tacticrafter.yaml repeats them)."""

    iterations: int = Field(
        default=10, ge=1, description="code iterations per player per episode (the paper's I is capped by this)"
    )
    causal: bool = Field(default=True, description='the causal model (false = ablation "no causal")')
    opponent: bool = Field(default=True, description='the opponent model (false = ablation "no opponent")')
    enable_causal: bool | None = Field(
        default=None,
        description="alias of `causal` (upstream's name, used by experiment=ablation_modules); null = causal",
    )
    enable_opponent: bool | None = Field(default=None, description="alias of `opponent`; null = opponent")
    preset_tactics: str | None = Field(
        default=None, description="a tactics text used instead of generating the first tactics"
    )
    update_tactics: bool = Field(
        default=True, description="false = keep the first (e.g. preset) tactics for the whole series"
    )
    checkpoint: str | None = Field(
        default=None, description="a directory to start from (a checkpoint, or an episode's team directory)"
    )
    roles: dict[str, dict[str, Any] | None] = Field(
        default={}, description="e.g. {action: {temperature: 0.0}, critic: {model: gpt-4o-mini}}"
    )
    attempts: int = Field(
        default=3, ge=1, description="calls per LLM step when an answer cannot be used (tags, JSON, code)"
    )
    min_llm_time_s: float = Field(
        default=5.0, ge=0, description="during the game, no LLM call starts with less time left than this"
    )
    quick_fail_s: float = Field(
        default=3.0, ge=0, description='a run that errors within this many seconds "failed at once" (not good code)'
    )
    restart_pause_s: float = Field(
        default=1.0, ge=0, description="wait before re-running code that ended within this many seconds"
    )
    max_llm_failures: int = Field(
        default=3, ge=1, description="per player and episode: failed code requests before it stops asking"
    )
    max_chat_lines: int = Field(default=60, ge=0, description="chat lines shown in a prompt (after deduplication)")
    max_tactics: int = Field(default=6, ge=1, description="numbered tactics items kept")
    keep_messages: bool = Field(default=True, description="write the prompts into tacticrafter.json")

    @field_validator("roles")
    @classmethod
    def _known_roles(cls, roles: dict[str, dict[str, Any] | None]) -> dict[str, dict[str, Any] | None]:
        unknown = sorted(set(roles) - set(ROLES))
        if unknown:
            raise ValueError(f"tacticrafter: unknown role(s) {unknown}; valid: {list(ROLES)}")
        role_settings(roles)  # validates the keys of each role
        return roles


class TactiCrafter(Team):
    name = "tacticrafter"
    uses_llm = True
    Options = TactiCrafterOptions

    def __init__(self, **options: object):
        super().__init__(**options)
        o = TactiCrafterOptions.model_validate(options)
        self.max_iterations = o.iterations
        self.causal_enabled = o.causal if o.enable_causal is None else o.enable_causal
        self.opponent_enabled = o.opponent if o.enable_opponent is None else o.enable_opponent
        self.preset_tactics = o.preset_tactics.strip() if o.preset_tactics and o.preset_tactics.strip() else None
        self.update_tactics = o.update_tactics
        self.roles = {k: dict(v or {}) for k, v in o.roles.items()}
        self.attempts = o.attempts
        self.min_llm_time_s, self.quick_fail_s = o.min_llm_time_s, o.quick_fail_s
        self.restart_pause_s, self.max_llm_failures = o.restart_pause_s, o.max_llm_failures
        self.max_chat_lines, self.max_tactics = o.max_chat_lines, o.max_tactics
        self.keep_messages = o.keep_messages
        self.memory = Memory()
        self.agents: list[BaseAgent] = []
        self.agent_names: list[str] = []
        self.llm: RoleLLM | None = None
        self.llm_off: str | None = None  # why LLM calls stopped for this episode
        self.calls = CallStats()
        self.record: dict[str, Any] = {}
        if o.checkpoint:
            self.load_checkpoint(Path(o.checkpoint))

    # --- helpers ---------------------------------------------------------------------------------

    def objective(self, ctx: TeamContext) -> str:
        return (
            f"You play for {ctx.side.team_name} with {', '.join(ctx.side.player_names)}. Win the game: when it "
            f"ends, {ctx.side.team_name} must have more points than {ctx.opponent.team_name}."
        )

    def tactics_text(self) -> str:
        return self.memory.tactics or "No team tactics: play the scenario as well as you can."

    def expected_latency(self, role: str) -> float:
        return self.calls.expected_latency(role)

    def note_call(self, role: str, asked: Asked) -> None:
        self.calls.add(self.record.setdefault("llm", {}), role, asked)
        if asked.budget_exceeded and not self.llm_off:
            self.llm_off = f"budget: {asked.error}"
            self.record["llm_off"] = self.llm_off

    def _module_record(self, name: str, asked: Asked | None, **extra: Any) -> dict:
        rec: dict[str, Any] = dict(extra)
        if asked is not None:
            self.note_call(name if name in ROLES else "tactics", asked)
            rec.update(ok=asked.ok, error=asked.error, attempts=asked.attempts)
            if self.keep_messages:
                rec["messages"] = asked.messages
        self.record.setdefault("modules", {})[name] = rec
        return rec

    # --- pre-game ----------------------------------------------------------------------------------

    async def pre_game(self, ctx: TeamContext) -> None:
        digests = self._start_record(ctx)
        has_events = any(digests.values())
        t0 = time.monotonic()
        graph_text = await self._causal_step(ctx, digests, has_events)  # 1. causal model
        await self._opponent_step(ctx, digests, has_events, graph_text)  # 2. opponent model
        await self._tactics_step(ctx, digests, has_events, graph_text)  # 3. tactics
        self.record["modules_s"] = round(time.monotonic() - t0, 3)
        await self._start_agents(ctx, digests)  # 4. base agents: first code of the episode, in parallel
        self._write(ctx)

    def _start_record(self, ctx: TeamContext) -> dict[str, list]:
        """Resets the episode's LLM, counters and record; returns last episode's digest per player."""
        players = ctx.side.player_names
        self.agent_names = agent_names(ctx.scenario)
        self.llm = RoleLLM(ctx.llm, self.roles) if ctx.llm is not None else None
        self.llm_off = None if self.llm is not None else "no LLM client (the match gave this team none)"
        self.iterations = [0] * len(players)
        mem = self.memory
        digests = {name: mem.events.get(name, []) for name in players}
        self.record = {
            "episode": ctx.episode,
            "team": ctx.side.team_name,
            "players": players,
            "protocol": ctx.protocol,
            "options": {
                "iterations": self.max_iterations,
                "causal": self.causal_enabled,
                "opponent": self.opponent_enabled,
                "preset_tactics": self.preset_tactics is not None,
                "update_tactics": self.update_tactics,
            },
            "roles": {r: self.llm.settings_for(r) for r in ROLES} if self.llm else {},
            "memory_from_episodes": mem.episodes,
            "modules": {},
            "llm": {},
        }
        if self.llm_off:
            self.record["llm_off"] = self.llm_off
        return digests

    async def _causal_step(self, ctx: TeamContext, digests: dict[str, list], has_events: bool) -> str:
        """1. The causal model: a first graph, or what last episode's chat and inventories add.
        Returns the graph as the other modules' prompts show it."""
        if not self.causal_enabled:
            return "(causal model disabled)"
        mem = self.memory
        if not len(mem.graph):
            if self._llm_ok():
                graph, asked = await causal.initial(self.llm, ctx.scenario, attempts=self.attempts)
                rec = self._module_record("causal", asked, step="initial")
                if graph is not None:
                    mem.graph = graph
                    rec["relations"] = len(graph)
                    rec["missing_modules"] = graph.missing_modules(list(ctx.scenario.primitives))
            else:
                self._module_record("causal", None, step="initial", skipped=self.llm_off)
        elif has_events:
            if self._llm_ok():
                evidence = own_chat_with_inventory(digests, max_lines=self.max_chat_lines)
                new, added = await causal.update(self.llm, ctx.scenario, mem.graph, evidence, attempts=self.attempts)
                rec = self._module_record("causal", added, step="update")
                if new is not None:
                    rec["merge"] = mem.graph.merge(new)
            else:
                self._module_record("causal", None, step="update", skipped=self.llm_off)
        return mem.graph.text()

    async def _opponent_step(
        self, ctx: TeamContext, digests: dict[str, list], has_events: bool, graph_text: str
    ) -> None:
        """2. The opponent model: from the second episode, the opponent's tactics guessed from its chat."""
        if not (self.opponent_enabled and has_events):
            return
        if not self._llm_ok():
            self._module_record("opponent", None, step="update", skipped=self.llm_off)
            return
        mem, opp = self.memory, ctx.opponent
        asked = await opponent.update(
            self.llm,
            opponent_team=opp.team_name,
            opponent_players=opp.player_names,
            objective=f"{opp.team_name} ({', '.join(opp.player_names)}) wants to end the game with more "
            f"points than {ctx.side.team_name}.",
            scenario=ctx.scenario.description(),
            graph=graph_text,
            chat_log=opponent_chat(
                digests,
                ctx.scenario,
                opp,
                max_lines=self.max_chat_lines,
                world_chat=ctx.last_episode.get("chat"),
            ),
            previous=mem.opponent_tactics or UNKNOWN,
            attempts=self.attempts,
            max_items=3,
        )
        self._module_record("opponent", asked, step="update")
        if asked.value is not None:
            mem.opponent_tactics, mem.opponent_source = asked.value, "inferred"
        else:
            mem.opponent_source = "kept"

    async def _tactics_step(
        self, ctx: TeamContext, digests: dict[str, list], has_events: bool, graph_text: str
    ) -> None:
        """3. The tactics module: preset, first written, updated from last episode's events, or kept."""
        mem = self.memory
        if mem.tactics is None and self.preset_tactics:
            mem.tactics, mem.tactics_source = self.preset_tactics, "preset"
            self._module_record("tactics", None, step="preset")
        elif mem.tactics is None:
            await self._initial_tactics(ctx, graph_text)
        elif has_events and self.update_tactics:
            await self._update_tactics(ctx, digests, graph_text, mem.tactics)
        else:
            mem.tactics_source = "kept"
            self._module_record("tactics", None, step="kept")

    def _brief(self, ctx: TeamContext, graph_text: str) -> dict[str, Any]:
        """What both tactics prompts are told: the team, its players, its objective, the scenario, the graph."""
        return {
            "team_name": ctx.side.team_name,
            "players": ctx.side.player_names,
            "objective": self.objective(ctx),
            "scenario": ctx.scenario.description(),
            "graph": graph_text,
        }

    async def _initial_tactics(self, ctx: TeamContext, graph_text: str) -> None:
        mem = self.memory
        if not self._llm_ok():
            self._module_record("tactics", None, step="initial", skipped=self.llm_off)
            return
        asked = await tactics.initial(
            self.llm,
            **self._brief(ctx, graph_text),
            attempts=self.attempts,
            max_items=self.max_tactics,
        )
        self._module_record("tactics", asked, step="initial")
        if asked.ok:
            mem.tactics, mem.tactics_source = asked.value, "generated"
        else:
            mem.tactics_source = "none"

    async def _update_tactics(self, ctx: TeamContext, digests: dict[str, list], graph_text: str, previous: str) -> None:
        mem = self.memory
        if not self._llm_ok():
            mem.tactics_source = "kept"
            self._module_record("tactics", None, step="update", skipped=self.llm_off)
            return
        asked = await tactics.update(
            self.llm,
            **self._brief(ctx, graph_text),
            chat_log=tail(longest_chat(digests), self.max_chat_lines),
            nearby_blocks=nearby_blocks_text(digests),
            inventories=inventories_text(digests),
            previous=previous,
            opponent=mem.opponent_tactics if self.opponent_enabled else "(opponent model disabled)",
            attempts=self.attempts,
            max_items=self.max_tactics,
        )
        self._module_record("tactics", asked, step="update")
        if asked.ok:
            mem.previous_tactics, mem.tactics, mem.tactics_source = mem.tactics, asked.value, "updated"
        else:
            mem.tactics_source = "kept"

    async def _start_agents(self, ctx: TeamContext, digests: dict[str, list]) -> None:
        """4. One base agent per player, each given its last code and chat; their first code in parallel."""
        self.agents = [BaseAgent(self, name, k) for k, name in enumerate(ctx.side.player_names)]
        for agent in self.agents:
            heard = digests.get(agent.name)
            chat = tail(chat_lines(heard), self.max_chat_lines) if heard else "No chat yet: the game has not started."
            agent.start_episode(ctx, self.memory.code.get(agent.name, {}), chat)
        await asyncio.gather(*(a.pre_game(ctx) for a in self.agents))

    def _llm_ok(self) -> bool:
        return self.llm is not None and not self.llm_off

    # --- game --------------------------------------------------------------------------------------

    async def play(self, ctx: TeamContext) -> None:
        self.iterations = [0] * len(self.agents)
        try:
            await asyncio.gather(*(a.play(ctx) for a in self.agents))
        finally:  # the whistle cancels the agents: what each did is read from it, once
            self.iterations = [a.iterations for a in self.agents]
            self.record["iterations"] = {a.name: a.iterations for a in self.agents}

    # --- post-game ---------------------------------------------------------------------------------

    async def post_game(self, ctx: TeamContext) -> None:
        players = ctx.side.player_names
        events = C.episode_events(ctx.last_episode, players)
        digests, self.record["dedup"] = digest_episode(events, players, self.agent_names or agent_names(ctx.scenario))
        self.memory.events.update(digests)
        self.record["iterations"] = {
            a.name: self.iterations[a.k] if a.k < len(self.iterations) else 0 for a in self.agents
        }
        for agent in self.agents:
            self.memory.code[agent.name] = agent.summary()
            self.record.setdefault("agents", {})[agent.name] = {**agent.record, "dedup_in_game": agent.stats.to_dict()}
        self.memory.episodes += 1
        self._write(ctx)

    def _write(self, ctx: TeamContext) -> None:
        ctx.out_dir.mkdir(parents=True, exist_ok=True)
        iters = {a.name: self.iterations[a.k] for a in self.agents if a.k < len(self.iterations)}
        self.memory.write(ctx.out_dir, episode=ctx.episode, iterations=iters)
        if not self.record.get("agents"):
            self.record["agents"] = {a.name: a.record for a in self.agents}
        (ctx.out_dir / "tacticrafter.json").write_text(json.dumps(self.record, indent=1, default=str))

    # --- checkpoint --------------------------------------------------------------------------------

    def state(self) -> dict[str, Any]:
        return self.memory.to_dict()

    def load_state(self, state: dict[str, Any]) -> None:
        self.memory = Memory.from_dict(state)

    def save_checkpoint(self, directory: Path) -> Path:
        path = super().save_checkpoint(directory)
        self.memory.write(Path(directory))
        return path

    def load_checkpoint(self, directory: Path) -> None:
        directory = Path(directory)
        if has_team_state(directory):
            super().load_checkpoint(directory)
        else:
            self.memory = Memory.read(directory)
