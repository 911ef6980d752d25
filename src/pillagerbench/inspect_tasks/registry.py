"""Inspect's entry point (`[project.entry-points.inspect_ai]` in pyproject.toml): importing this
module registers the tasks, so `inspect eval pillagerbench/mushroom_war` and `inspect list` find them."""

from .tasks import dash_and_dine, generalization, mushroom_war

__all__ = ["dash_and_dine", "generalization", "mushroom_war"]
