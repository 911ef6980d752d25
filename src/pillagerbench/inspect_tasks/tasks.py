"""The tasks: `pillagerbench/mushroom_war`, `pillagerbench/dash_and_dine` (one scenario, the paper's
layout unless -T split=test) and `pillagerbench/generalization` (both scenarios, the team on both
sides, on the paper's layout and on fresh test layouts: our experiment=generalization).

    inspect eval pillagerbench/mushroom_war --model openai/gpt-4o -T opponents=balanced,passive -T episodes=5
    inspect eval pillagerbench/mushroom_war --model-role red=openai/gpt-4o --model-role blue=anthropic/claude-sonnet-4-0
    inspect eval pillagerbench/mushroom_war --model openai/gpt-4o -T team=agent --solver my_agent.py

Arguments (-T): team (cot; tacticrafter or any registered team; agent: the Inspect agent, the task's
solver or --solver, plays the team through the game's tools: seated.py), opponents (default do_nothing and
the scenario's built-in opponents), sides (red; red,blue), split (paper; test, dev, or several),
layout (instead of split: every episode on this layout, a seed or a layout file), episodes per
sample (one series), episode_length, paper (upstream's scoring and step protocol),
seed, run_dir. A sample is one series; Inspect's --epochs plays each again on other seeds.
"""

from __future__ import annotations

from typing import Any

from inspect_ai import Task, task
from inspect_ai.dataset import MemoryDataset, Sample
from inspect_ai.model import model_roles

from pillagerbench.match.run import scenario_from_config
from pillagerbench.rundir import SeriesSpec
from pillagerbench.teams.tools import briefing

from .args import AGENT, TaskArgs, parse, run_root, series, side_of
from .default_agent import team_agent
from .scorer import series_score
from .seated import end_series, seat_series
from .solver import play_series


def sample(spec: SeriesSpec, seated: bool = False) -> Sample:
    """One series; an agent's (`seated`) has the briefing as its input: what the agent is told of the game."""
    side = side_of(spec)
    arena = spec.config.split or "paper"
    summary = f"{spec.scenario}: {spec.red} (red) vs {spec.blue} (blue), {spec.episodes} episode(s) on {arena} layouts"
    return Sample(
        id=spec.id,
        input=f"{briefing(scenario_from_config(spec.config), side)}\n\n({summary})" if seated else summary,
        metadata={"series": spec.to_dict(), "side": side, "opponent": spec.blue if side == "red" else spec.red},
    )


def make_task(name: str, scenarios: tuple[str, ...], given: dict[str, Any], **defaults: Any) -> Task:
    if "layout" in given:  # a layout of the user's replaces the task's splits
        defaults.pop("split", None)
    args: TaskArgs = parse(name, scenarios, {**defaults, **given})
    specs = series(name, args, model_roles())
    root, seated = str(run_root(name, args)), args.team == AGENT
    return Task(
        dataset=MemoryDataset([sample(s, seated) for s in specs], name=f"pillagerbench_{name}"),
        # the agent's series starts in the setup step, which a --solver does not replace (seated.py)
        setup=seat_series(root, name) if seated else None,
        solver=team_agent() if seated else play_series(root, name),
        cleanup=end_series if seated else None,
        scorer=series_score(),
        metadata={"scenarios": list(scenarios), "team": args.team},
    )


@task
def mushroom_war(**args: Any) -> Task:
    """Mushroom War: the team against each opponent (one series per opponent, side and arena)."""
    return make_task("mushroom_war", ("mushroom_war",), args)


@task
def dash_and_dine(**args: Any) -> Task:
    """Dash & Dine: the team against each opponent (one series per opponent, side and arena)."""
    return make_task("dash_and_dine", ("dash_and_dine",), args)


@task
def generalization(**args: Any) -> Task:
    """Unseen arenas: both scenarios, both sides, the paper's layout and fresh test layouts."""
    return make_task(
        "generalization", ("mushroom_war", "dash_and_dine"), args, sides="red,blue", split="paper,test", episodes=3
    )
