"""Experiments: the paper's experiment designs as lists of series, run in parallel, resumable (docs/experiments.md)."""

from pillagerbench.experiments.spec import SeriesSpec, build_series, builtin_teams

__all__ = ["SeriesSpec", "build_series", "builtin_teams"]
