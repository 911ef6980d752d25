"""The task arguments (`inspect eval pillagerbench/mushroom_war -T team=cot -T opponents=balanced`)
and the series they make: our generalization design (experiments/spec.py) with the task's scenarios,
team, opponents, sides and arenas, so a sample is one series (opponent, side, arena) built exactly
as `pillagerbench run experiment=generalization` builds it. With model roles for both sides
(`--model-role red=... --model-role blue=...`) the team plays itself: model against model. With
`team=agent` the Inspect agent plays the team from a seat each sample opens (seated.py).

A bad argument is one line naming it and what is accepted (`TaskArgumentError`, which Inspect prints
without a traceback); nothing is started and no run directory is written.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from inspect_ai._util.error import PrerequisiteError

from pillagerbench.config.compose import ConfigError
from pillagerbench.config.sides import SIDES
from pillagerbench.config.validate import layout_problems, load_run, team_problems
from pillagerbench.experiments.spec import build_series, slug
from pillagerbench.rundir import SeriesSpec
from pillagerbench.scenarios.layout import PAPER, SPLITS
from pillagerbench.teams import TEAMS, find_team
from pillagerbench.teams.tools import AgentTeam

AGENT = AgentTeam.name  # -T team=agent: the Inspect agent plays the team through the game's tools (seated.py)
ARGS = (
    "team",
    "opponents",
    "sides",
    "split",
    "layout",
    "episodes",
    "episode_length",
    "paper",
    "seed",
    "clock",
    "run_dir",
)


class TaskArgumentError(PrerequisiteError):
    """A task argument Inspect was given that cannot work: one line, no traceback, nothing started."""

    def __init__(self, task: str, message: str):
        super().__init__(f"pillagerbench/{task}: {message}")


@dataclass(frozen=True)
class TaskArgs:
    scenarios: tuple[str, ...]
    team: str = "cot"
    opponents: tuple[str, ...] = ()  # () = do_nothing and the scenario's built-in opponents
    sides: tuple[str, ...] = ("red",)
    splits: tuple[str, ...] = ("paper",)  # each: every episode on the paper's layout, or a fresh one of the split
    layout: str | int | None = None  # every episode on this layout (a seed or a layout file) instead of a split
    episodes: int = 1  # per sample (one series: the team keeps what it learned; the paper plays 5)
    episode_length: int | None = None  # None: the scenario's
    paper: bool = False  # upstream's scoring and step protocol (paper=true)
    seed: int | None = None
    clock: str | None = None  # None: the run's default (real); lockstep: an LLM call holds the world (docs/clock.md)
    run_dir: str | None = None  # where the series directories go; None: runs/inspect/<time>_<task>


def names(value: Any) -> tuple[str, ...]:
    """A list argument as given on Inspect's command line (`a,b`) or in Python (a list)."""
    if value is None:
        return ()
    items = value if isinstance(value, (list, tuple)) else str(value).split(",")
    return tuple(str(v).strip() for v in items if str(v).strip())


def parse(task: str, scenarios: Iterable[str], given: dict[str, Any]) -> TaskArgs:
    """The task's arguments checked: an unknown one, a side, a split or a number out of range is refused."""
    unknown = sorted(set(given) - set(ARGS))
    if unknown:
        raise TaskArgumentError(task, f"unknown task argument {unknown[0]!r}; accepted: {', '.join(ARGS)}")
    args = TaskArgs(
        scenarios=tuple(scenarios),
        team=str(given.get("team") or "cot"),
        opponents=names(given.get("opponents")),
        sides=names(given.get("sides")) or ("red",),
        splits=names(given.get("split")) or ("paper",),
        layout=given.get("layout"),
        episodes=_number(task, "episodes", given.get("episodes", 1)),
        episode_length=None
        if given.get("episode_length") is None
        else _number(task, "episode_length", given["episode_length"]),
        paper=_flag(task, "paper", given.get("paper", False)),
        seed=None if given.get("seed") is None else _number(task, "seed", given["seed"], least=0),
        clock=None if given.get("clock") is None else str(given["clock"]),
        run_dir=given.get("run_dir"),
    )
    if args.layout is not None and given.get("split") is not None:
        raise TaskArgumentError(task, f"layout={args.layout} and split={given['split']}: give one or the other")
    for key, values, known in (("sides", args.sides, SIDES), ("split", args.splits, tuple(SPLITS))):
        bad = [v for v in values if v not in known]
        if bad:
            raise TaskArgumentError(task, f"{key}={bad[0]!r} is not one; accepted: {', '.join(known)}")
    return args


def _number(task: str, key: str, value: Any, least: int = 1) -> int:
    try:
        n = int(value)
    except (TypeError, ValueError):
        n = least - 1
    if n < least or isinstance(value, bool) or str(n) != str(value).strip():
        raise TaskArgumentError(task, f"{key}={value!r}: a whole number ≥ {least}")
    return n


def _flag(task: str, key: str, value: Any) -> bool:
    if isinstance(value, bool) or str(value).lower() in ("true", "false"):
        return str(value).lower() == "true"
    raise TaskArgumentError(task, f"{key}={value!r}: true or false")


def overrides(args: TaskArgs, roles: Iterable[str]) -> list[str]:
    """The `pillagerbench run` overrides of the series: the generalization design, llm=inspect."""
    both = set(SIDES) <= set(roles)  # model against model: the team plays itself, one model per side
    opponents = (args.team,) if both else args.opponents
    sides = ("red",) if both else args.sides
    argv = [
        "experiment=generalization",
        f"experiment.scenarios=[{','.join(args.scenarios)}]",
        f"experiment.team={args.team}",
        f"experiment.sides=[{','.join(sides)}]",
        *(f"experiment.arenas.{split}={args.episodes if split in args.splits else 0}" for split in SPLITS),
        "llm=inspect",
        "llm.preflight=false",  # Inspect checks its models itself; a preflight call would be one more answer
    ]
    if opponents:
        argv.append(f"experiment.opponents=[{','.join(opponents)}]")
    if args.episode_length:
        argv.append(f"episode_length={args.episode_length}")
    if args.paper:
        argv.append("paper=true")
    if args.seed is not None:
        argv.append(f"seed={args.seed}")
    if args.clock is not None:  # checked with the rest of the config (series()): a bad one names the clocks
        argv.append(f"clock={args.clock}")
    return argv


def series(task: str, args: TaskArgs, roles: Iterable[str]) -> list[SeriesSpec]:
    """The series of the task (one per sample), every team and the model roles checked."""
    roles = [r for r in roles if r in SIDES]
    refused = agent_problem(args, roles)
    if refused:
        raise TaskArgumentError(task, refused)
    argv = overrides(args, roles)
    try:
        cfg = load_run(argv, teams=False)
        specs = build_series(cfg, argv)
    except ConfigError as exc:
        raise TaskArgumentError(task, str(exc).splitlines()[0]) from None
    if args.layout is not None:
        specs = [on_layout(task, spec, args.layout) for spec in specs]
    for spec in specs:
        problems = team_problems(spec.config)  # each series' teams, their options and LLM settings, as a run's
        problems = [p for p in problems if p not in UNSEATED]  # the agent's seat is opened per sample (seated.py)
        if problems:
            raise TaskArgumentError(task, problems[0])
        for side in roles:
            team = spec.red_team if side == "red" else spec.blue_team
            if not getattr(find_team(team), "uses_llm", False):
                llm_teams = ", ".join(n for n, c in TEAMS.items() if getattr(c, "uses_llm", False))
                raise TaskArgumentError(
                    task,
                    f"model role {side!r} given, but {side} plays {team}, which is not an LLM team "
                    f"(LLM teams: {llm_teams}; roles: red, blue)",
                )
    return specs


# what the agent team says before its sample's seat is opened (by the setup step, seated.py)
UNSEATED = {f"{side}.{problem}" for side in SIDES for problem in AgentTeam.check_options({})}


def agent_problem(args: TaskArgs, roles: list[str]) -> str | None:
    """Why the agent team cannot play as asked: it plays from the seat of a sample, which only the task's
    team has, one agent against the opponents."""
    if AGENT in args.opponents:
        return f"opponents={AGENT}: only the task's team is played by the Inspect agent (-T team={AGENT})"
    if args.team == AGENT and set(SIDES) <= set(roles):
        return (
            f"team={AGENT} with model roles for both sides: the Inspect agent plays one side against the "
            "opponents, not model against model (give --model, or an LLM team as team=)"
        )
    return None


def on_layout(task: str, spec: SeriesSpec, layout: str | int) -> SeriesSpec:
    """A series of the paper's arena played on `layout` instead (every episode), named by it."""
    config = spec.config.updated({"layout": layout, "split": None})
    problems = layout_problems(config)
    if problems:
        raise TaskArgumentError(task, problems[0])
    name = spec.id.removesuffix(f"_{PAPER}") + f"_layout-{slug(Path(str(layout)).stem)}"
    return dataclasses.replace(spec, id=name, config=config)


def run_root(task: str, args: TaskArgs) -> Path:
    """The directory the task's series directories go in."""
    if args.run_dir:
        return Path(args.run_dir)
    return Path("runs") / "inspect" / f"{time.strftime('%Y-%m-%d_%H-%M-%S')}_{task}"


def side_of(spec: SeriesSpec) -> str:
    """The side the task's team plays in a series (red when it plays itself)."""
    return "blue" if spec.red != spec.variant and spec.blue == spec.variant else "red"
