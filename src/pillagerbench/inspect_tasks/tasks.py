"""The tasks: `pillagerbench/mushroom_war`, `pillagerbench/dash_and_dine` (one scenario, the paper's
layout unless -T split=test) and `pillagerbench/generalization` (both scenarios, the team on both
sides, on the paper's layout and on fresh test layouts: our experiment=generalization).

    inspect eval pillagerbench/mushroom_war --model openai/gpt-4o -T opponents=balanced,passive -T episodes=5
    inspect eval pillagerbench/mushroom_war --model-role red=openai/gpt-4o --model-role blue=anthropic/claude-sonnet-4-0

Arguments (-T): team (cot; tacticrafter or any registered team), opponents (default do_nothing and
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

from pillagerbench.rundir import SeriesSpec

from .args import TaskArgs, parse, run_root, series, side_of
from .scorer import series_score
from .solver import play_series


def sample(spec: SeriesSpec) -> Sample:
    side = side_of(spec)
    arena = spec.config.split or "paper"
    return Sample(
        id=spec.id,
        input=f"{spec.scenario}: {spec.red} (red) vs {spec.blue} (blue), {spec.episodes} episode(s) on {arena} layouts",
        metadata={"series": spec.to_dict(), "side": side, "opponent": spec.blue if side == "red" else spec.red},
    )


def make_task(name: str, scenarios: tuple[str, ...], given: dict[str, Any], **defaults: Any) -> Task:
    if "layout" in given:  # a layout of the user's replaces the task's splits
        defaults.pop("split", None)
    args: TaskArgs = parse(name, scenarios, {**defaults, **given})
    specs = series(name, args, model_roles())
    return Task(
        dataset=MemoryDataset([sample(s) for s in specs], name=f"pillagerbench_{name}"),
        solver=play_series(str(run_root(name, args)), name),
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
