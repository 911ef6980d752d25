"""The one LLM client: any OpenAI-compatible endpoint through the official `openai` SDK.

    client = LLMClient.from_config(cfg, run_dir=run_dir)     # cfg from load_config([...])
    red = client.for_team("red")                             # own budget; shared ledger/cache
    answer = await red.complete([{"role": "user", "content": "..."}], role="action")
    plan = await red.complete_json("Reply in JSON ...", role="tactics")
    red.reset_episode()                                      # at the start of each episode

Retries are ours (the SDK's max_retries is 0), so the ledger's `retries` is exact: 429 (waiting
what retry-after says), 408/409/5xx, timeouts, connection errors, garbled bodies and empty
answers are retried with exponential backoff up to `max_retries`; 400/401/403/404 are not.
Every request carries the headers X-PillagerBench-Role and X-PillagerBench-Team (the fake
server matches rules on the role).
"""

from __future__ import annotations

import asyncio
import email.utils
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import openai

from pillagerbench.config_schema import LLMCacheConfig, LLMLedgerConfig, RunConfig

from . import errors as E
from .budget import Budget
from .cache import LLMCache, normalize_mode
from .ledger import Ledger
from .parsing import parse_json, strip_think
from .prices import Price, price_of, price_problem
from .protocol import ROLE_HEADER, TEAM_HEADER
from .settings import LLMSettings

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

    @property
    def truncated(self) -> bool:
        return self.finish_reason == "length"


class LLMClient:
    def __init__(
        self,
        settings: LLMSettings,
        *,
        team: str | None = None,
        ledger: Ledger | None = None,
        cache: LLMCache | None = None,
        budget: Budget | None = None,
        price: Price | None = None,
        _sdk: openai.AsyncOpenAI | None = None,
    ):
        self.settings = settings
        self.team = team
        self.price = price if price is not None else price_of(settings)  # llm/prices.py
        self.ledger = ledger
        self.cache = cache if cache is not None else LLMCache(None, "off")
        self.budget = budget if budget is not None else self._default_budget()
        self._owns_sdk = _sdk is None
        self._sdk = _sdk or openai.AsyncOpenAI(
            api_key=settings.api_key(), base_url=settings.base_url, max_retries=0, timeout=settings.timeout
        )

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
            self.settings,
            team=team,
            ledger=self.ledger,
            cache=self.cache,
            budget=budget,
            price=self.price,
            _sdk=self._sdk,
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
        if self._owns_sdk:
            await self._sdk.close()
        if self.ledger is not None and self._owns_sdk:
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
        """One chat completion. `params` (stop, seed, top_p, response_format, ...) go into the body.
        Raises an LLMError subclass; every call, failed or not, is one ledger record."""
        s = self.settings
        ctx: dict[str, Any] = {"role": role, "team": self.team, "model": s.model, "provider": s.provider}
        request = self.build_request(messages, temperature=temperature, max_tokens=max_tokens, **params)
        start = time.perf_counter()
        key, sample = "", 0
        reserved = False
        try:
            self.budget.reserve(**ctx)
            reserved = True
            key, sample = self.cache.key(s.provider, request)
            entry = self.cache.get(key) if self.cache.reads else None
            if entry is not None:
                return self._answer(role, request, entry["response"], start, 0, True, key, sample)
            if self.cache.mode == "replay":
                raise E.CacheMiss(
                    f"replay: request not in the cache {self.cache.dir} (key {key}, sample {sample})", key=key, **ctx
                )
            response = await self._send(request, role, ctx)
            retries = response.pop("retries")
            self.cache.put(
                key, {"key": key, "sample": sample, "provider": s.provider, "request": request, "response": response}
            )
            return self._answer(role, request, response, start, retries, False, key, sample)
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
        return LLMResponse(
            text=text,
            raw_text=raw,
            finish_reason=response.get("finish_reason"),
            input_tokens=tin,
            output_tokens=tout,
            latency_s=latency,
            retries=retries,
            cache_hit=cache_hit,
            model=response.get("model") or self.settings.model,
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

    async def _send(self, request: dict, role: str, ctx: dict) -> dict:
        """POST with our retry loop; returns the cacheable answer plus `retries`."""
        s = self.settings
        headers = {**s.extra_headers, ROLE_HEADER: role, TEAM_HEADER: self.team or ""}
        body = {k: v for k, v in request.items() if k not in ("model", "messages")}
        attempt = 0
        while True:
            t0 = time.perf_counter()
            try:
                completion = await self._sdk.chat.completions.create(
                    model=request["model"],
                    messages=request["messages"],
                    extra_body=body,
                    extra_headers=headers,
                    timeout=s.timeout,
                )
                answer = self._read(completion, ctx)
                answer.update(latency_s=round(time.perf_counter() - t0, 6), retries=attempt)
                return answer
            except Exception as exc:  # noqa: BLE001 - mapped to an LLMError below
                err, wait = self._map_error(exc, ctx)
            if not err.retryable or attempt >= s.max_retries:
                err.retries = attempt  # type: ignore[attr-defined]
                raise err from None  # the SDK's exception may quote headers: keep it off the chain
            if wait is None:
                wait = s.retry_backoff_s * (2**attempt)
            await asyncio.sleep(max(0.0, min(wait, s.retry_max_wait_s)))
            attempt += 1

    def _read(self, completion: Any, ctx: dict) -> dict:
        choices = getattr(completion, "choices", None)
        if not choices or getattr(choices[0], "message", None) is None:
            raise E.MalformedResponse(f"answer without choices: {str(completion)[:200]}", **ctx)
        raw = choices[0].message.content or ""
        text = strip_think(raw) if self.settings.strip_think else raw
        if not text.strip():
            raise E.EmptyResponse(f"empty answer (finish_reason={choices[0].finish_reason})", **ctx)
        usage = getattr(completion, "usage", None)
        return {
            "raw_text": raw,
            "finish_reason": choices[0].finish_reason,
            "input_tokens": getattr(usage, "prompt_tokens", None),
            "output_tokens": getattr(usage, "completion_tokens", None),
            "model": getattr(completion, "model", None),
        }

    @staticmethod
    def _map_error(exc: Exception, ctx: dict) -> tuple[E.LLMError, float | None]:
        """Our error for an SDK/parse failure, and the wait the provider asked for (if any)."""
        if isinstance(exc, E.LLMError):
            return exc, None
        if isinstance(exc, openai.APITimeoutError):
            return E.LLMTimeout(f"no answer within the timeout: {exc}", **ctx), None
        if isinstance(exc, openai.APIConnectionError):
            cause = exc.__cause__ or exc
            return E.LLMConnectionError(f"cannot reach the provider: {exc} ({cause})", **ctx), None
        if isinstance(exc, openai.APIStatusError):
            status = exc.status_code
            body = exc.body
            message = body.get("message") if isinstance(body, dict) and body.get("message") else exc.message
            kind: type[E.LLMError] = {
                401: E.AuthenticationFailed,
                403: E.AuthenticationFailed,
                404: E.ModelNotFound,
                400: E.BadRequest,
                422: E.BadRequest,
                429: E.RateLimited,
            }.get(status, E.ProviderError)
            if kind is E.ProviderError and 400 <= status < 500 and status not in (408, 409):
                kind = E.BadRequest
            return kind(f"HTTP {status}: {message}", status=status, **ctx), _retry_after(exc.response)
        if isinstance(exc, (ValueError, openai.APIResponseValidationError)):
            return E.MalformedResponse(f"answer is not a chat completion: {exc}", **ctx), None
        raise exc

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


def _retry_after(response: Any) -> float | None:
    """Seconds from retry-after-ms or retry-after (seconds or an HTTP date)."""
    headers = getattr(response, "headers", None) or {}
    try:
        if (ms := headers.get("retry-after-ms")) is not None:
            return float(ms) / 1000
        if (value := headers.get("retry-after")) is not None:
            try:
                return float(value)
            except ValueError:
                when = email.utils.parsedate_to_datetime(value)
                return max(0.0, when.timestamp() - time.time())
    except (TypeError, ValueError):
        return None
    return None
