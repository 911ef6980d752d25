"""`pillagerbench run ... plan=true`: what a run would play, how long it would take on this machine,
how many LLM calls it would make and what they would cost; nothing is played (no server, no run
directory). docs/experiments.md ("Before a run: plan=true") lists the assumptions; in short:

- Series and episodes: the experiment's own (experiments/spec.py), or the one match of a plain run;
  with resume=RUN_DIR only the episodes still to play.
- Wall time, on the clock the run plays (plan_clock.py): each series costs its clock's series
  overhead (server start, logins) plus per episode its game seconds times the clock's wall seconds per
  game second (1 on the real clock; on the lockstep clock lockstep's measured cost, scaled by this
  machine's speed now and by the matches sharing its cores), the clock's episode overhead (arena
  reset, pre- and post-game of built-in teams) and, for LLM teams, the pre-game's chain of LLM calls
  at an assumed latency (on the lockstep clock also the game's calls: the world waits for them); the
  series are then scheduled as runner.run_all does (`parallel` at once, in order, each after the
  series it starts from), plus the run's overhead once. The real clock's overheads were measured with
  `python benchmarks/plan_accuracy.py --overheads`, lockstep's with `--clock lockstep` (figures in
  docs/experiments.md).
- LLM calls per team and episode: cot, one call in the pre-game (up to `attempts` when answers
  cannot be used); tacticrafter, in the pre-game the causal model (if on), the opponent model (if
  on, from the second episode), the tactics (unless preset or frozen) and one action call per
  player, each up to `attempts`; in the game up to (iterations - 1) critic + action pairs per
  player (none at the low end). `random` and the built-in teams make none.
- Tokens per call: input = the role's prompt files rendered with the scenario's description and
  primitives documentation (measured now, at about 4 characters per token), at the high end plus
  the dynamic parts (chat lines up to the team's cap, the last answer shown back); output = a
  quarter of the output cap (`max_tokens`) at the low end, the cap at the high end.
- Cost: tokens at the model's price (llm/prices.py); a model with no known price is "unknown".
"""

from __future__ import annotations

import functools
import heapq
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pillagerbench.config.schema import RunConfig
from pillagerbench.config.sides import SIDES
from pillagerbench.experiments.how_many import how_many
from pillagerbench.experiments.plan_clock import COSTS, Machine
from pillagerbench.experiments.spec import SeriesSpec, build_series, launch_order
from pillagerbench.llm.tokens import count_tokens
from pillagerbench.teams.entrant import entrant_of

# Assumed, not measured (no provider is reachable here): seconds per LLM call in a pre-game chain
LATENCY_LOW_S = 2.0
OUTPUT_TOKENS_PER_S = 50.0  # the high end's latency: the output cap at this rate, plus LATENCY_LOW_S
LOW_OUTPUT_SHARE = 0.25  # the low end's answers use this share of the output cap
CHAT_LINE_TOKENS = 20  # a chat line shown in a prompt (the high end's dynamic part)
SHOW_SERIES = 40  # series listed one per line; the rest are counted


@dataclass
class Calls:
    """LLM calls of one team over some episodes: counts and tokens, low and high."""

    low: int = 0
    high: int = 0
    in_low: int = 0
    in_high: int = 0
    out_low: int = 0
    out_high: int = 0
    chain_low: float = 0.0  # seconds of pre-game LLM calls in sequence
    chain_high: float = 0.0
    game_chain_high: float = 0.0  # seconds of the game's LLM calls in sequence (the lockstep world waits)

    def add(self, n_low: int, n_high: int, prompt: tuple[int, int], cap: int) -> None:
        self.low, self.high = self.low + n_low, self.high + n_high
        self.in_low += n_low * prompt[0]
        self.in_high += n_high * prompt[1]
        self.out_low += int(n_low * cap * LOW_OUTPUT_SHARE)
        self.out_high += n_high * cap

    def __iadd__(self, other: Calls) -> Calls:
        for k in self.__dataclass_fields__:
            setattr(self, k, getattr(self, k) + getattr(other, k))
        return self


@dataclass
class ModelCost:
    label: str  # provider model
    price: Any  # llm.prices.Price
    calls: Calls = field(default_factory=Calls)

    def cost(self) -> tuple[float | None, float | None]:
        c = self.calls
        return self.price.cost(c.in_low, c.out_low), self.price.cost(c.in_high, c.out_high)


@dataclass
class SeriesPlan:
    spec: SeriesSpec
    episodes: int  # still to play
    teams: dict[str, str]  # side -> "team" or "team (LLM provider model)"
    wall_low: float
    wall_high: float
    game_wall_s: float = 0.0  # wall seconds one episode's game takes (its clock's cost, plan_clock.py)


@dataclass
class Plan:
    title: str
    series: list[SeriesPlan]
    episode_length: float
    parallel: int
    parallel_note: str | None
    wall_low: float
    wall_high: float
    models: dict[str, ModelCost]
    retries: int = 0  # an episode spoiled on our side is played again up to this many times (not estimated)
    how_many: list[str] = field(default_factory=list)  # episodes a question needs (how_many.py)
    clock: str = "real"  # the clock the wall time assumes (plan_clock.py)
    clock_line: str = ""  # what the clock's wall time assumed (plan_clock.ClockCost.says)
    overheads: tuple[float, float, float] = (0.0, 0.0, 0.0)  # wall seconds per series, episode, run

    @property
    def episodes(self) -> int:
        return sum(s.episodes for s in self.series)


# --- prompt sizes -------------------------------------------------------------------------------


@functools.lru_cache(maxsize=8)
def _scenario_texts(scenario: str) -> tuple[int, int, int]:
    """(tokens of the scenario's description, of its primitives' docs, players per side)."""
    from pillagerbench.players import primitives as prim
    from pillagerbench.scenarios import make_scenario

    sc = make_scenario(scenario)
    return (
        count_tokens(sc.description()),
        count_tokens(prim.docs([*sc.primitives, "mineflayer"])),
        len(sc.sides[0].players),
    )


@functools.lru_cache(maxsize=64)
def _template_tokens(team: str, names: tuple[str, ...]) -> tuple[int, bool, bool]:
    """Tokens of the prompt files `names` of a team, and whether they take the scenario and primitives."""
    if team == "cot":
        from pillagerbench.teams.cot.team import PROMPTS
    else:
        from pillagerbench.teams.tacticrafter.templates import PROMPTS
    texts = [PROMPTS[n] for n in names]
    return (
        sum(count_tokens(t.text) for t in texts),
        any("scenario" in t.placeholders for t in texts),
        any("primitives" in t.placeholders for t in texts),
    )


def _prompt(team: str, names: tuple[str, ...], scenario: str, dynamic: int) -> tuple[int, int]:
    """(low, high) input tokens of one call: the files with the scenario's texts; high adds `dynamic`."""
    base, has_scenario, has_primitives = _template_tokens(team, names)
    desc, docs, _ = _scenario_texts(scenario)
    low = base + (desc if has_scenario else 0) + (docs if has_primitives else 0)
    return low, low + dynamic


# --- calls per team -----------------------------------------------------------------------------


def _latency_high(cap: int) -> float:
    return LATENCY_LOW_S + cap / OUTPUT_TOKENS_PER_S


def team_calls(team: str, options: dict, llm: Any, scenario: str, episodes: range, upstream: bool) -> Calls:
    """LLM calls of one team over the given episode indices (module docstring: the assumptions)."""
    calls = Calls()
    cap = int(llm.max_tokens or 512)
    attempts = max(1, int(options.get("attempts") or 3))
    _, _, players = _scenario_texts(scenario)
    if team == "cot":
        cap = int(options.get("max_tokens") or cap)
        n = 1 if upstream else attempts
        chat = int(options.get("max_chat_lines") or 0) * CHAT_LINE_TOKENS
        for _ in episodes:
            names = ("system", "user") + ("code_format",) * players
            calls.add(1, n, _prompt("cot", names, scenario, chat + cap), cap)
            calls.chain_low += LATENCY_LOW_S
            calls.chain_high += n * _latency_high(cap)
        return calls
    if team != "tacticrafter":
        return calls
    roles = options.get("roles") or {}

    def role_cap(role: str) -> int:
        return int((roles.get(role) or {}).get("max_tokens") or cap)

    causal = options.get("causal", True) if options.get("enable_causal") is None else options["enable_causal"]
    opponent = options.get("opponent", True) if options.get("enable_opponent") is None else options["enable_opponent"]
    iterations = max(1, int(options.get("iterations") or 10))
    chat = int(options.get("max_chat_lines") or 0) * CHAT_LINE_TOKENS
    for k in episodes:
        chain_low = chain_high = 0.0
        steps: list[tuple[str, tuple[str, ...]]] = []
        if causal:
            steps.append(("causal", ("causal_initial",) if k == 0 else ("causal_update",)))
        if opponent and k > 0:
            steps.append(("opponent", ("opponent_system", "opponent_user")))
        if k == 0 and not options.get("preset_tactics"):
            steps.append(("tactics", ("tactics_system", "tactics_examples", "tactics_initial")))
        elif k > 0 and options.get("update_tactics", True):
            steps.append(("tactics", ("tactics_system", "tactics_examples", "tactics_update")))
        for role, names in steps:
            c = role_cap(role)
            calls.add(1, attempts, _prompt("tacticrafter", names, scenario, chat + c), c)
            chain_low, chain_high = chain_low + LATENCY_LOW_S, chain_high + attempts * _latency_high(c)
        act, crit = role_cap("action"), role_cap("critic")
        action_prompt = _prompt("tacticrafter", ("action_system", "action_user"), scenario, chat + act)
        critic_prompt = _prompt("tacticrafter", ("critic_system", "critic_user"), scenario, chat)
        calls.add(players, players * (1 if upstream else attempts), action_prompt, act)  # first code, in parallel
        chain_low, chain_high = chain_low + LATENCY_LOW_S, chain_high + attempts * _latency_high(act)
        later = players * (iterations - 1)  # in the game: a critic and an action call per later iteration
        calls.add(0, later, action_prompt, act)
        calls.add(0, later, critic_prompt, crit)
        calls.game_chain_high += (iterations - 1) * (_latency_high(act) + _latency_high(crit))  # players at once
        calls.chain_low += chain_low
        calls.chain_high += chain_high
    return calls


# --- the plan -----------------------------------------------------------------------------------


def _sides(cfg: RunConfig) -> list[tuple[str, str, dict, Any]]:
    """(side, team, options with defaults, LLMSettings or None) of a series config."""
    from pillagerbench.llm.settings import LLMSettings
    from pillagerbench.teams import declared_options, find_team

    out = []
    for side in SIDES:
        name = cfg.side(side).name
        cls = find_team(name)
        options = {**declared_options(name, cls), **cfg.side(side).options}
        llm = LLMSettings.from_config(cfg.llm_of(side)) if cls.uses_llm else None
        out.append((side, name, options, llm))
    return out


def schedule(specs: list[SeriesSpec], durations: dict[str, float], parallel: int) -> float:
    """Seconds until every series has finished, started as runner.run_all starts them."""
    pending = launch_order(specs)
    running: list[tuple[float, str]] = []
    done: set[str] = set()
    now = 0.0
    while pending or running:
        for s in list(pending):
            if len(running) >= parallel:
                break
            if all(d in done for d in s.after):
                pending.remove(s)
                heapq.heappush(running, (now + durations[s.id], s.id))
        if not running:  # a dependency that never finishes (run_all skips these)
            break
        now, sid = heapq.heappop(running)
        done.add(sid)
    return now


def _specs(cfg: RunConfig, argv: list[str]) -> tuple[str, list[SeriesSpec], dict[str, int]]:
    """(title, series, planned episodes already settled per series: used or given up) of what the
    command would run; a new experiment's series checked (teams, options, LLM settings)."""
    from pillagerbench.config.schema import check
    from pillagerbench.config.validate import team_problems
    from pillagerbench.experiments.runner import load_experiment, series_progress

    if cfg.resume:
        title, specs, dirs = load_experiment(Path(cfg.resume))
        done = {s.id: series_progress(s, dirs[s.id]) for s in specs}
        return title, specs, {sid: p.used + p.given_up for sid, p in done.items()}
    if cfg.experiment is not None:  # its series checked as a run checks them, without the preflight
        specs = build_series(cfg, argv)
        check(list(dict.fromkeys(line for s in specs for line in team_problems(s.config))))
        return str(cfg.experiment["name"]), specs, {}
    red, blue, scenario = cfg.red.name, cfg.blue.name, cfg.scenario.name
    spec = SeriesSpec("run", 0, "run", scenario, red, blue, red, blue, cfg.episodes, cfg.seed, cfg)
    return f"run {scenario}: red {red} vs blue {blue}", [spec], {}


def _parallel(cfg: RunConfig, clock: str, cpus: int | None, load: float | None) -> tuple[int, str | None]:
    """Series at once, as the run would choose (a plain run plays one match)."""
    from pillagerbench.experiments.runner import local_parallel

    if cfg.experiment is None and not cfg.resume:
        return 1, None
    if cfg.launcher == "ray":
        if cfg.parallel:
            return cfg.parallel, None
        return 1, "launcher=ray without parallel: planned as 1 at once (give parallel=N)"
    return local_parallel(cfg, clock=clock, cpus=cpus, load=load)


def _machine(clock: str, cpus: int | None, load: float | None, speed_ms: float | None) -> Machine:
    """This machine as the plan assumes it; the speed probe runs only for a lockstep plan."""
    import os

    from pillagerbench.host.machine import core_speed_ms

    if load is None:
        load = os.getloadavg()[0] if hasattr(os, "getloadavg") else 0.0
    if speed_ms is None and clock == "lockstep":
        speed_ms = core_speed_ms()
    return Machine(cpus or os.cpu_count() or 1, load, speed_ms)


@dataclass
class _Chains:
    """One series' LLM calls in sequence, in seconds: the pre-game's (the larger side's: they think at
    once) and the game's (both sides' summed: on the lockstep clock the world waits for each)."""

    low: float = 0.0
    high: float = 0.0
    game_high: float = 0.0

    def add(self, calls: Calls) -> None:
        self.low, self.high = max(self.low, calls.chain_low), max(self.high, calls.chain_high)
        self.game_high += calls.game_chain_high


def build_plan(
    cfg: RunConfig,
    argv: list[str],
    *,
    cpus: int | None = None,
    load: float | None = None,
    speed_ms: float | None = None,
) -> Plan:
    """The plan of a run; `cpus`, `load` and `speed_ms` (host/machine.core_speed_ms) stand for this
    machine's when given."""
    from pillagerbench.experiments.runner import clock_of
    from pillagerbench.llm.prices import price_of

    title, specs, finished = _specs(cfg, argv)
    clock = clock_of(specs) if specs else cfg.clock.mode
    parallel, note = _parallel(cfg, clock, cpus, load)
    machine = _machine(clock, cpus, load, speed_ms)
    at_once = max(1, min(parallel, len(specs)))  # matches sharing the cores
    models: dict[str, ModelCost] = {}
    plans, low, high = [], {}, {}
    for s in specs:
        todo = range(finished.get(s.id, 0), s.episodes)
        chains, teams = _Chains(), {}
        for side, name, options, llm in _sides(s.config):
            teams[side] = entrant_of(s.config, side).label  # the entrant, as its records will name it
            if llm is None:
                continue
            calls = team_calls(name, options, llm, s.scenario, todo, s.config.protocol == "upstream")
            if not calls.high:
                continue
            label = f"{llm.provider} {llm.model}"
            teams[side] = f"{teams[side]} (LLM {label})"
            models.setdefault(label, ModelCost(label, price_of(llm))).calls += calls
            chains.add(calls)
        cost = COSTS[s.config.clock.mode]
        n = len(todo)
        per_episode = s.config.episode_length * cost.per_game_s(s.scenario, s.config.clock, at_once, machine)
        per_series, beyond_game, _ = cost.overheads(at_once, machine, len(specs))
        base = (per_series if n else 0.0) + n * (per_episode + beyond_game)
        game_high = chains.game_high if cost.game_calls_wait else 0.0
        low[s.id], high[s.id] = base + chains.low, base + chains.high + game_high
        plans.append(SeriesPlan(s, n, teams, low[s.id], high[s.id], per_episode))
    cost = COSTS[clock]
    overheads = cost.overheads(at_once, machine, len(specs))
    return Plan(
        title=title,
        series=plans,
        episode_length=cfg.episode_length,
        parallel=parallel,
        parallel_note=note,
        wall_low=overheads[2] + schedule(specs, low, parallel),
        wall_high=overheads[2] + schedule(specs, high, parallel),
        models=models,
        retries=cfg.retries,
        how_many=how_many(
            sorted({s.scenario for s in specs}), cfg.plan_width, cfg.plan_difference, _per_episode(models, plans)
        ),
        clock=clock,
        overheads=overheads,
        clock_line=cost.says(cfg.clock if not specs else specs[0].config.clock, at_once, machine),
    )


def _per_episode(models: dict[str, ModelCost], plans: list[SeriesPlan]) -> tuple[float, float] | None:
    """This run's LLM cost per episode, low and high (None without LLM teams or a price)."""
    episodes = sum(p.episodes for p in plans)
    costs = [m.cost() for m in models.values()]
    if not episodes or not costs or any(lo is None or hi is None for lo, hi in costs):
        return None
    return sum(lo or 0.0 for lo, _ in costs) / episodes, sum(hi or 0.0 for _, hi in costs) / episodes


# --- printing -----------------------------------------------------------------------------------


def duration(seconds: float) -> str:
    seconds = round(seconds)
    h, rest = divmod(seconds, 3600)
    m, s = divmod(rest, 60)
    if h:
        return f"{h} h {m:02d} min"
    return f"{m} min {s:02d} s" if m else f"{s} s"


def _usd(value: float | None) -> str:
    return "?" if value is None else (f"${value:.4f}" if value < 1 else f"${value:,.2f}")


def lines(plan: Plan) -> list[str]:
    out = [f"plan: {plan.title} (nothing is played: no server, no run directory)"]
    out.append(f"series: {len(plan.series)}")
    for sp in plan.series[:SHOW_SERIES]:
        out.append(f"  {sp.spec.id}: {sp.episodes} episode(s), red {sp.teams['red']} vs blue {sp.teams['blue']}")
    if len(plan.series) > SHOW_SERIES:
        out.append(f"  ... and {len(plan.series) - SHOW_SERIES} more series")
    out.append(f"episodes: {plan.episodes} of {plan.episode_length:g} s")
    out.append(
        f"retries: {plan.retries}: an episode spoiled on our side (provider unreachable, crash, lag) is played "
        f"again, up to {plan.retries} more per planned episode (not in the figures below)"
    )
    out.append(f"parallel: {plan.parallel} at once" + (f" ({plan.parallel_note})" if plan.parallel_note else ""))
    wall = duration(plan.wall_low)
    cost = COSTS[plan.clock]
    if plan.wall_high > plan.wall_low + 1:
        thinking = "pre-game and game" if cost.game_calls_wait else "pre-game"
        wall = f"{wall} to {duration(plan.wall_high)} (LLM {thinking} time at {LATENCY_LOW_S:g} s a call to the output cap at {OUTPUT_TOKENS_PER_S:g} tokens/s)"
    out.append(plan.clock_line)
    series, episode, _ = plan.overheads
    out.append(
        f"wall time: {wall}; per series {series:.3g} s and per episode {episode:.3g} s "
        "beyond the game (measured, benchmarks/plan_accuracy.py)"
    )
    if not plan.models:
        out.append("LLM calls: none (no team of this run uses an LLM)")
    for label, m in plan.models.items():
        c = m.calls
        out.append(
            f"LLM calls ({label}): {c.low:,} to {c.high:,}; input tokens {c.in_low:,} to {c.in_high:,}, "
            f"output tokens {c.out_low:,} to {c.out_high:,}"
        )
        lo, hi = m.cost()
        if lo is None or hi is None:
            out.append(
                f"cost ({label}): unknown ({c.high:,} calls unpriced: {m.price.source}); "
                "give a price with llm.price.input_per_1m=USD llm.price.output_per_1m=USD"
            )
        else:
            out.append(
                f"cost ({label}): {_usd(lo)} to {_usd(hi)} at ${m.price.input_per_1m:g} / "
                f"${m.price.output_per_1m:g} per million input / output tokens ({m.price.source})"
            )
    if plan.models:
        out.append("assumptions: calls, tokens and latency as in docs/experiments.md (Before a run: plan=true)")
    return out + plan.how_many


def main_plan(cfg: RunConfig, argv: list[str]) -> int:
    """`pillagerbench run ... plan=true`: print the plan, play nothing. An experiment's series are
    checked as a run checks them (teams, options, LLM settings), without the preflight."""
    for line in lines(build_plan(cfg, argv)):
        print(line)
    return 0
