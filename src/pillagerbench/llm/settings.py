"""Typed view of one `llm` config group entry (see conf/llm/*.yaml for the meaning of each field).

It holds the NAME of the key's environment variable, never the key: the key is read when a
client is made and handed straight to the SDK.
"""

from __future__ import annotations

import importlib.util
import os
from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from typing import TYPE_CHECKING, Any

from .errors import LLMConfigError
from .redact import register_secret

if TYPE_CHECKING:
    from pillagerbench.config.schema import LLMKeys

INSPECT = "inspect"  # the provider whose calls go through Inspect's model API (inspect_model.py)
EVAL_MODEL = "eval"  # llm=inspect llm.model=eval: the Inspect evaluation's model (or the side's model role)
INSPECT_EXTRA = "pip install 'pillagerbench[inspect]'"
NO_KEY = "no-key"  # sent to servers that need none, so the SDK never falls back to OPENAI_API_KEY


@dataclass(frozen=True)
class LLMSettings:
    provider: str = "openai_compatible"
    base_url: str = "http://127.0.0.1:8080/v1"
    model: str = "local"
    api_key_env: str | None = None
    temperature: float | None = 0.3
    max_tokens: int | None = 512
    timeout: float = 60.0
    max_retries: int = 3
    retry_backoff_s: float = 1.0
    retry_max_wait_s: float = 30.0
    system_role: str = "system"  # system | developer
    send_temperature: bool = True
    max_tokens_param: str = "max_tokens"  # max_tokens | max_completion_tokens
    strip_think: bool = True
    extra_headers: dict[str, str] = field(default_factory=dict)
    extra_body: dict[str, Any] = field(default_factory=dict)
    price_input_per_1m: float | None = None  # USD per million input tokens; None = the price table's (prices.py)
    price_output_per_1m: float | None = None
    budget: dict[str, float | None] = field(default_factory=dict)  # per team and episode
    preflight: bool = True  # one short request before episode 0 (llm/preflight.py)

    @classmethod
    def from_config(cls, cfg: LLMKeys | Mapping[str, Any]) -> LLMSettings:
        """From the `llm` settings a side plays with (typed: RunConfig.llm_of), or an `llm` node (a composed
        node or a plain dict), its keys as composed."""
        from pillagerbench.config.schema import LLMKeys

        data = (cfg if isinstance(cfg, LLMKeys) else LLMKeys.of(cfg)).given()
        price = data.pop("price", None) or {}
        data.setdefault("price_input_per_1m", price.get("input_per_1m"))
        data.setdefault("price_output_per_1m", price.get("output_per_1m"))
        known = {f.name for f in fields(cls)}
        unknown = sorted(set(data) - known)
        if unknown:
            raise LLMConfigError(f"unknown llm settings {unknown}; valid: {sorted(known)}")
        for name in ("extra_headers", "extra_body", "budget"):
            data[name] = dict(data.get(name) or {})
        settings = cls(**data)
        if settings.system_role not in ("system", "developer"):
            raise LLMConfigError(f"llm.system_role must be system or developer, not {settings.system_role!r}")
        if settings.max_tokens_param not in ("max_tokens", "max_completion_tokens"):
            raise LLMConfigError("llm.max_tokens_param must be max_tokens or max_completion_tokens")
        if settings.provider == INSPECT and not inspect_installed():
            raise LLMConfigError(
                f"llm=inspect needs the inspect extra, which is not installed: {INSPECT_EXTRA} (or choose another llm= preset)"
            )
        return settings

    def api_key(self) -> str:
        """The key from the environment (registered for redaction), or a placeholder if none is needed."""
        if not self.api_key_env:
            return NO_KEY
        value = os.environ.get(self.api_key_env)
        if not value:
            raise LLMConfigError(
                f"environment variable {self.api_key_env} is not set "
                f"(llm.api_key_env names the variable holding the key for {self.provider})"
            )
        register_secret(value)
        return value


def inspect_installed() -> bool:
    """Whether inspect-ai (the optional extra behind llm=inspect) can be imported, without importing it."""
    try:
        return importlib.util.find_spec("inspect_ai") is not None
    except (ImportError, ValueError):  # ValueError: its sys.modules entry is None (blocked)
        return False
