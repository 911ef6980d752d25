"""The configuration's schema: every top-level key and the `llm` node typed with pydantic (types,
ranges, choices). `problems(model, data)` gives one line per problem, naming the key, the bad value
and what is valid. Groups (scenario, teams) are checked against their registries in validate.py.
"""

from __future__ import annotations

import socket
from typing import Any, Literal

from omegaconf import OmegaConf
from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator
from pydantic_core import PydanticCustomError

from pillagerbench.config import ENV_NAME, ConfigError, looks_like_key, to_dict

SECRET = "secret"  # the error type of a value that must not be echoed (problems() names the key only)


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")


class ServerConfig(_Strict):
    host: str
    port: int = Field(ge=0, le=65535)
    view_distance: int = Field(ge=1, le=32)
    crop_growth_chance: float = Field(ge=0, le=1)
    tps: float = Field(ge=1, le=200)
    operators: list[str]
    log_dir: str | None


class LLMCacheConfig(_Strict):
    mode: Literal["off", "read", "write", "readwrite", "replay"]
    dir: str | None


class LLMLedgerConfig(_Strict):
    content: Literal["full", "hash"]


class LLMConfig(_Strict):
    """The `llm` node (the fields of LLMSettings, with ranges)."""

    provider: str
    base_url: str
    model: str
    api_key_env: str | None
    temperature: float | None = Field(default=None, ge=0, le=2)
    max_tokens: int | None = Field(default=None, ge=1)
    timeout: float = Field(gt=0)
    max_retries: int = Field(ge=0)
    retry_backoff_s: float = Field(ge=0)
    retry_max_wait_s: float = Field(ge=0)
    system_role: Literal["system", "developer"]
    send_temperature: bool
    max_tokens_param: Literal["max_tokens", "max_completion_tokens"]
    strip_think: bool
    preflight: bool
    extra_headers: dict[str, str]
    extra_body: dict[str, Any]
    price: dict[Literal["input_per_1m", "output_per_1m"], float | None]
    budget: dict[Literal["max_calls", "max_input_tokens", "max_output_tokens", "max_cost_usd"], float | None]

    @field_validator("api_key_env")
    @classmethod
    def _a_variable_name(cls, value: str | None) -> str | None:
        """The NAME of the variable holding the key; a key here would be echoed and recorded."""
        if value is None or (ENV_NAME.fullmatch(value) and not looks_like_key(value)):
            return value
        what = "looks like a key, not" if looks_like_key(value) else "is not"
        raise PydanticCustomError(
            SECRET,
            f"{what} the name of an environment variable; put the key in a variable (export OPENAI_API_KEY=...) "
            "and give its name: llm.api_key_env=OPENAI_API_KEY",
        )


class RunConfig(BaseModel):
    """The top-level keys of conf/config.yaml (groups are checked on their own)."""

    model_config = ConfigDict(extra="ignore")

    server: ServerConfig
    llm_cache: LLMCacheConfig
    llm_ledger: LLMLedgerConfig
    episodes: int = Field(ge=1)
    episode_length: float = Field(gt=0)
    seed: int
    run_dir: str | None
    display: Literal["auto", "live", "plain"]
    scoring: Literal["clean", "upstream"] = "clean"  # runs from before these keys: the defaults
    protocol: Literal["pillagerbench", "upstream"] = "pillagerbench"
    paper: bool = False  # sets scoring and protocol to upstream's (config.PAPER)
    watch: int | None = Field(None, ge=0, le=65535)
    retries: int = Field(2, ge=0)  # replays of a spoiled episode (rundir/schedule.py); older runs: the default
    layout: int | str = "paper"  # checked in full by validate.layout_problems
    split: str | None = None
    parallel: int | None = Field(ge=1)
    launcher: Literal["local", "ray"]
    ray_address: str | None
    resume: str | None
    calibration: str | None
    plan: bool = False  # runs from before this key: the default


def _where(prefix: str, loc: tuple) -> str:
    return ".".join([prefix, *map(str, loc)] if prefix else map(str, loc))


def problems(model: type[BaseModel], data: Any, prefix: str = "") -> list[str]:
    """One line per problem of `data` (a dict or an OmegaConf node) against `model`."""
    if OmegaConf.is_config(data):
        data = OmegaConf.to_container(data, resolve=True)
    try:
        model.model_validate(data)
    except ValidationError as exc:
        out = []
        for e in exc.errors(include_url=False):
            key = _where(prefix, e["loc"])
            if e["type"] == "extra_forbidden":
                out.append(f"{key}: unknown key")
            elif e["type"] == "missing":
                out.append(f"{key}: missing")
            elif e["type"] == SECRET:
                out.append(f"{key}: {e['msg']}")
            else:
                out.append(f"{key}={e.get('input')!r}: {e['msg'][0].lower() + e['msg'][1:]}")
        return out
    return []


def top_level_problems(cfg: Any) -> list[str]:
    """Problems of the top-level keys of a composed config (conf/config.yaml)."""
    data = to_dict(cfg)
    if data.get("llm_cache", {}).get("mode") in (None, False):  # YAML 1.1 reads a bare `off` as false
        data["llm_cache"]["mode"] = "off"
    return problems(RunConfig, data)


def watch_problems(cfg: Any) -> list[str]:
    """`watch=PORT`: a port number, free on the server's host (0 = any free port)."""
    data = to_dict(cfg)
    watch = data.get("watch")
    if watch is None:
        return []
    if isinstance(watch, bool) or not isinstance(watch, int) or not 0 <= watch <= 65535:
        return [f"watch={watch!r}: a port number 0..65535 (0 = a free port), or null for no live view"]
    host = str((data.get("server") or {}).get("host", "127.0.0.1"))
    if watch and not port_is_free(host, watch):
        return [f"watch={watch}: port {host}:{watch} is already in use (choose another, or watch=0 for a free port)"]
    return []


def port_is_free(host: str, port: int) -> bool:
    with socket.socket(socket.AF_INET6 if ":" in host else socket.AF_INET, socket.SOCK_STREAM) as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            s.bind((host, port))
        except OSError:
            return False
    return True


def check(lines: list[str]) -> None:
    """Raise one ConfigError holding every line, if any."""
    if lines:
        raise ConfigError("\n".join(lines))
