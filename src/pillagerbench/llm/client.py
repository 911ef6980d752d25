"""The one LLM client: any OpenAI-compatible endpoint through the official `openai` SDK.

    client = LLMClient.from_config(cfg, run_dir=run_dir)     # cfg from load_config([...])
    red = client.for_team("red")                             # own budget; shared ledger/cache
    answer = await red.complete([{"role": "user", "content": "..."}], role="action")
    plan = await red.complete_json("Reply in JSON ...", role="tactics")
    red.reset_episode()                                      # at the start of each episode

A client is one team's asking: the request it builds, its budget, the ledger's record of every call,
the game clock's hold while it waits. The answer comes from its `Transport` (transport.py: the cache,
else the provider through provider.py, whose retries are ours, so the ledger's `retries` is exact),
shared by every client of a run.
Every request carries the headers X-PillagerBench-Role and X-PillagerBench-Team (the fake
server matches rules on the role).
"""

from __future__ import annotations

import asyncio
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from pillagerbench.config.schema import LLMCacheConfig, LLMLedgerConfig, RunConfig

from . import errors as E
from .budget import Budget
from .cache import LLMCache, normalize_mode
from .ledger import Ledger
from .parsing import parse_json, strip_think
from .prices import Price, price_of, price_problem
from .settings import LLMSettings
from .thinking import Thinking
from .transport import Transport

Messages = str | Sequence[Mapping[str, Any]]
_UNSET: Any = object()


@dataclass(frozen=True)
class LLMResponse:
    text: str  # the answer, <think> blocks removed
    raw_text: str  # the answer as the provider sent it
    finish_reason: str | None
    input_tokens: int | None
    output_tokens: int | None
    latency_s: float
    retries: int
    cache_hit: bool
    model: str
    sample: int
    cache_key: str
    tool_calls: tuple[dict[str, Any], ...] = ()  # as the provider sent them (OpenAI shape); read by tool_calls.py

    @property
    def truncated(self) -> bool:
        return self.finish_reason == "length"

    @classmethod
    def of(
        cls,
        response: Mapping[str, Any],
        *,
        text: str,
        latency_s: float,
        retries: int,
        cache_hit: bool,
        model: str,
        sample: int,
        cache_key: str,
    ) -> LLMResponse:
        """The answer in the cacheable response (provider.send's shape); `model` when it names none."""
        return cls(
            text=text,
            raw_text=response.get("raw_text") or "",
            finish_reason=response.get("finish_reason"),
            input_tokens=response.get("input_tokens"),
            output_tokens=response.get("output_tokens"),
            latency_s=latency_s,
            retries=retries,
            cache_hit=cache_hit,
            model=response.get("model") or model,
            sample=sample,
            cache_key=cache_key,
            tool_calls=tuple(response.get("tool_calls") or ()),
        )


class LLMClient:
    def __init__(
        self,
        settings: LLMSettings,
        *,
        team: str | None = None,
        ledger: Ledger | None = None,
        cache: LLMCache | None = None,
        transport: Transport | None = None,
        budget: Budget | None = None,
        price: Price | None = None,
        thinking: Thinking | None = None,
    ):
        """Without a transport, the client opens its own (over `cache`, else none) and owns it and the ledger:
        `aclose` closes them; a client given one (`for_team`, a role's model) shares them and closes neither."""
        self.settings = settings
        self.thinking = thinking if thinking is not None else Thinking()  # the game clock's hold (thinking.py)
        self.team = team
        self.price = price if price is not None else price_of(settings)  # llm/prices.py
        self.ledger = ledger
        self.budget = budget if budget is not None else self._default_budget()
        self._owns = transport is None
        self.transport = transport if transport is not None else Transport.open(settings, cache)

    @property
    def cache(self) -> LLMCache:
        return self.transport.cache

    @classmethod
    def from_config(
        cls,
        cfg: Any,
        *,
        team: str | None = None,
        run_dir: str | Path | None = None,
        ledger: Ledger | None = None,
        cache: LLMCache | None = None,
    ) -> LLMClient:
        """From the full config (a run's configuration: sections llm, llm_cache, llm_ledger) or just
        its `llm` node (the cache and ledger then as the schema's defaults)."""
        if "llm" in cfg:
            run = RunConfig.of(cfg)
            settings, cache_cfg, ledger_cfg = LLMSettings.from_config(run.llm), run.llm_cache, run.llm_ledger
        else:
            settings, cache_cfg, ledger_cfg = LLMSettings.from_config(cfg), LLMCacheConfig(), LLMLedgerConfig()
        return cls.from_settings(
            settings, cache_cfg, ledger_cfg, team=team, run_dir=run_dir, ledger=ledger, cache=cache
        )

    @classmethod
    def from_settings(
        cls,
        settings: LLMSettings,
        cache_cfg: LLMCacheConfig,
        ledger_cfg: LLMLedgerConfig,
        *,
        team: str | None = None,
        run_dir: str | Path | None = None,
        ledger: Ledger | None = None,
        cache: LLMCache | None = None,
    ) -> LLMClient:
        """With run_dir, the ledger is `<run_dir>/llm_calls.jsonl` and the cache (unless mode off)
        is llm_cache.dir or `<run_dir>/llm_cache`."""
        if ledger is None and run_dir is not None:
            ledger = Ledger(Path(run_dir), content=ledger_cfg.content)
        if cache is None:
            mode = normalize_mode(cache_cfg.mode)
            directory = cache_cfg.dir or (Path(run_dir) / "llm_cache" if run_dir else None)
            if mode != "off" and directory is None:
                raise E.LLMConfigError(f"llm_cache.mode={mode} needs llm_cache.dir or a run directory")
            cache = LLMCache(directory, mode)
        return cls(settings, team=team, ledger=ledger, cache=cache)

    def for_team(self, team: str, budget: Budget | None = None) -> LLMClient:
        """A client for one team: same provider connection, ledger and cache; its own budget."""
        return LLMClient(
            self.settings, team=team, ledger=self.ledger, transport=self.transport, budget=budget, price=self.price
        )

    def _default_budget(self) -> Budget:
        problem = price_problem(self.settings)
        if problem:  # a dollar budget that could never trip
            raise E.LLMConfigError(problem)
        return Budget.from_limits(self.settings.budget, self.price.input_per_1m, self.price.output_per_1m)

    def reset_episode(self) -> None:
        """Start a new episode: the per-episode budget counters go back to zero."""
        self.budget.reset()

    async def aclose(self) -> None:
        if self._owns:
            await self.transport.aclose()
            if self.ledger is not None:
                self.ledger.close()

    async def __aenter__(self) -> LLMClient:
        return self

    async def __aexit__(self, *exc: object) -> None:
        await self.aclose()

    def __repr__(self) -> str:
        s = self.settings
        return (
            f"LLMClient(provider={s.provider!r}, model={s.model!r}, base_url={s.base_url!r}, "
            f"team={self.team!r}, cache={self.cache.mode!r})"
        )

    # -- requests --------------------------------------------------------------------------------
    def build_request(
        self, messages: Messages, *, temperature: Any = _UNSET, max_tokens: Any = _UNSET, **params: Any
    ) -> dict[str, Any]:
        """The request body exactly as it is sent (and keyed in the cache)."""
        s = self.settings
        if isinstance(messages, str):
            messages = [{"role": "user", "content": messages}]
        msgs = []
        for m in messages:
            m = dict(m)
            if m.get("role") in ("system", "developer"):
                m["role"] = s.system_role
            msgs.append(m)
        request: dict[str, Any] = {"model": s.model, "messages": msgs}
        temperature = s.temperature if temperature is _UNSET else temperature
        if s.send_temperature and temperature is not None:
            request["temperature"] = temperature
        max_tokens = s.max_tokens if max_tokens is _UNSET else max_tokens
        if max_tokens is not None:
            request[s.max_tokens_param] = max_tokens
        request.update(s.extra_body)
        request.update({k: v for k, v in params.items() if v is not None})
        return request

    async def complete(
        self, messages: Messages, *, role: str, temperature: Any = _UNSET, max_tokens: Any = _UNSET, **params: Any
    ) -> LLMResponse:
        """One chat completion (`params`: stop, seed, top_p, ... into the body); an LLMError subclass, or
        one ledger record per call, failed or not. The lockstep clock waits for it (`thinking`)."""
        async with self.thinking.held():
            answer = await self._complete(messages, role, temperature, max_tokens, params)
        await self.thinking.charged(answer.output_tokens)
        return answer

    async def _complete(
        self, messages: Messages, role: str, temperature: Any, max_tokens: Any, params: dict[str, Any]
    ) -> LLMResponse:
        s = self.settings
        ctx: dict[str, Any] = {"role": role, "team": self.team, "model": s.model, "provider": s.provider}
        request = self.build_request(messages, temperature=temperature, max_tokens=max_tokens, **params)
        start = time.perf_counter()
        key, sample = "", 0
        reserved = False
        try:
            self.budget.reserve(**ctx)
            reserved = True
            key, sample = self.transport.key(s, request)
            got = await self.transport.fetch(s, request, key, sample, role=role, team=self.team, ctx=ctx)
            return self._answer(role, request, got.response, start, got.retries, got.cache_hit, key, sample)
        except E.LLMError as err:
            self._log(role, request, None, start, getattr(err, "retries", 0), False, key, sample, err)
            self.budget.note_failure(err)
            raise
        except asyncio.CancelledError:
            # cancelled by the caller (a deadline, the whistle): still one ledger record
            self._log(role, request, None, start, 0, False, key, sample, E.Cancelled("call cancelled", **ctx))
            raise
        finally:
            if reserved:
                self.budget.release()

    def _answer(
        self,
        role: str,
        request: dict,
        response: dict,
        start: float,
        retries: int,
        cache_hit: bool,
        key: str,
        sample: int,
    ) -> LLMResponse:
        raw = response.get("raw_text") or ""
        text = strip_think(raw) if self.settings.strip_think else raw
        tin, tout = response.get("input_tokens"), response.get("output_tokens")
        cost = self.budget.charge(tin, tout, self.price.cost(tin, tout))
        latency = time.perf_counter() - start
        extra = {"orig_latency_s": response.get("latency_s")} if cache_hit else {}
        self._log(
            role, request, response, start, retries, cache_hit, key, sample, None, latency=latency, cost=cost, **extra
        )
        return LLMResponse.of(
            response,
            text=text,
            latency_s=latency,
            retries=retries,
            cache_hit=cache_hit,
            model=self.settings.model,
            sample=sample,
            cache_key=key,
        )

    def _log(
        self,
        role: str,
        request: dict,
        response: dict | None,
        start: float,
        retries: int,
        cache_hit: bool,
        key: str,
        sample: int,
        err: E.LLMError | None,
        *,
        latency: float | None = None,
        cost: float | None = 0.0,
        **extra: Any,
    ) -> None:
        if self.ledger is None:
            return
        s = self.settings
        self.ledger.record(
            request=request,
            response=response,
            team=self.team,
            role=role,
            provider=s.provider,
            model=s.model,
            latency_s=round(time.perf_counter() - start if latency is None else latency, 6),
            input_tokens=(response or {}).get("input_tokens"),
            output_tokens=(response or {}).get("output_tokens"),
            retries=retries,
            finish_reason=(response or {}).get("finish_reason"),
            cache_hit=cache_hit,
            cache_key=key or None,
            sample=sample,
            cost_usd=cost,  # None: unknown (no price for the model, or no usage reported)
            price=self.price.to_dict(),
            error_type=type(err).__name__ if err else None,
            error=str(err) if err else None,
            **extra,
        )

    async def complete_json(self, messages: Messages, *, role: str, attempts: int = 3, **kw: Any) -> Any:
        """Ask for JSON and parse the answer; re-ask (showing the model its bad answer) up to
        `attempts` calls in all, then raise InvalidJSON. Each call is a ledger record."""
        msgs = self.build_request(messages)["messages"]
        last = ""
        for _ in range(max(1, attempts)):
            answer = await self.complete(msgs, role=role, **kw)
            try:
                return parse_json(answer.text)
            except ValueError as exc:
                last = answer.text
                why = "It was cut off by the token limit; give a shorter answer." if answer.truncated else ""
                msgs = msgs + [
                    {"role": "assistant", "content": answer.text},
                    {
                        "role": "user",
                        "content": f"Your answer could not be parsed as JSON ({exc}). {why}"
                        "Send the JSON value again and nothing else.",
                    },
                ]
        raise E.InvalidJSON(
            f"no valid JSON after {attempts} attempts; last answer: {last[:200]!r}",
            role=role,
            team=self.team,
            model=self.settings.model,
            provider=self.settings.provider,
        )
