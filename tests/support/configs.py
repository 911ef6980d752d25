"""The composed configuration as a test's series carries it: `RunConfig`, typed."""

from __future__ import annotations

from functools import lru_cache

from pillagerbench.config.compose import load_config
from pillagerbench.config.schema import RunConfig


@lru_cache
def run_config(*overrides: str) -> RunConfig:
    """conf/config.yaml composed with `overrides`, typed (cached: composing takes Hydra a moment)."""
    return RunConfig.of(load_config(list(overrides)))
