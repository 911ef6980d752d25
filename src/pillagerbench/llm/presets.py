"""LLM presets and the clients of a match.

The presets are the `llm` config group: one file per provider set-up in `pillagerbench/conf/llm/`
(`llm=openai`, `llm=ollama`, ...), looked up by Hydra when the config is composed; that group is
their one registry. A side's team may override keys of the chosen preset (`red.llm.model=...`).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Protocol

from pillagerbench.config.registry import Registry
from pillagerbench.config.schema import RunConfig

from .client import LLMClient
from .settings import LLMSettings

PRESET_DIR = Path(__file__).resolve().parent.parent / "conf" / "llm"


def presets() -> Registry[Path]:
    """The presets `llm=NAME` accepts, each with its file (`base` holds the shared defaults and is not one)."""
    return Registry("llm preset", {p.stem: p for p in sorted(PRESET_DIR.glob("*.yaml")) if p.stem != "base"})


class MaybeLLMTeam(Protocol):
    @property
    def uses_llm(self) -> bool: ...  # a Team's class attribute (teams/base.py)


def make_llms(cfg: RunConfig, teams: Mapping[str, MaybeLLMTeam], run_dir: Path) -> dict[str, LLMClient]:
    """A client for each side whose team uses an LLM (the run's `llm` with the side's own keys,
    `red.llm.model=...`); they share the run directory's ledger and cache."""
    return {
        side: LLMClient.from_settings(
            LLMSettings.from_config(cfg.llm_of(side)), cfg.llm_cache, cfg.llm_ledger, team=side, run_dir=run_dir
        )
        for side, team in teams.items()
        if team.uses_llm
    }
