"""Hydra configuration: `pillagerbench <command> key=value group=option ...`.

Configs live in `pillagerbench/conf` (groups: `llm`, later `scenario`, `team`, `experiment`).
We use Hydra's compose API so every sub-command takes the same override syntax.
"""

from __future__ import annotations

from typing import Any

from hydra import compose, initialize_config_module
from hydra.core.global_hydra import GlobalHydra
from hydra.errors import HydraException
from omegaconf import DictConfig, OmegaConf


class ConfigError(ValueError):
    """Bad configuration or override; the message names the problem and the valid choices."""


# `red=cot` chooses an option of the `team` group for the red side (Hydra spells it `team@red=cot`);
# `red.llm.model=...` still sets a key inside it.
GROUP_ALIASES = {"red": "team@red", "blue": "team@blue"}


def _alias(override: str) -> str:
    key, sep, value = override.partition("=")
    if sep and key in GROUP_ALIASES:
        return f"{GROUP_ALIASES[key]}={value}"
    side, _, rest = key.partition(".")
    if sep and side in GROUP_ALIASES and rest.startswith("llm."):
        return f"++{override}"  # a side's LLM overrides may name keys its team config leaves out
    return override


def load_config(overrides: list[str] | None = None, config_name: str = "config") -> DictConfig:
    GlobalHydra.instance().clear()
    try:
        with initialize_config_module(config_module="pillagerbench.conf", version_base="1.3"):
            cfg = compose(config_name=config_name, overrides=[_alias(o) for o in overrides or []])
    except HydraException as exc:  # unknown group option, bad override syntax, ...
        raise ConfigError(str(exc)) from None
    OmegaConf.set_readonly(cfg, False)
    return cfg


def to_dict(cfg: Any) -> dict[str, Any]:
    """A config node (a mapping) as plain Python data, interpolations resolved."""
    data = OmegaConf.to_container(cfg, resolve=True)
    if not isinstance(data, dict):
        raise ConfigError(f"expected a mapping, got {type(data).__name__}: {data!r}")
    return {str(k): v for k, v in data.items()}
