"""One request to the provider, through the official `openai` SDK, with our retries (the SDK's
max_retries is 0, so the ledger's `retries` is exact): 429 (waiting what retry-after says),
408/409/5xx, timeouts, connection errors, garbled bodies and empty answers are retried with
exponential backoff up to `max_retries`; 400/401/403/404 are not. Every SDK failure becomes one of
our LLMErrors (errors.py). The client (client.py) decides what to send, caches and records.
"""

from __future__ import annotations

import asyncio
import email.utils
import time
from typing import Any

import openai

from . import errors as E
from .headers import ROLE_HEADER, TEAM_HEADER
from .parsing import strip_think
from .settings import LLMSettings


async def send(
    sdk: openai.AsyncOpenAI, s: LLMSettings, request: dict, *, role: str, team: str | None, ctx: dict
) -> dict:
    """POST with our retry loop; returns the cacheable answer plus `retries`."""
    headers = {**s.extra_headers, ROLE_HEADER: role, TEAM_HEADER: team or ""}
    body = {k: v for k, v in request.items() if k not in ("model", "messages")}
    attempt = 0
    while True:
        t0 = time.perf_counter()
        try:
            completion = await sdk.chat.completions.create(
                model=request["model"],
                messages=request["messages"],
                extra_body=body,
                extra_headers=headers,
                timeout=s.timeout,
            )
            answer = read(completion, s, ctx)
            answer.update(latency_s=round(time.perf_counter() - t0, 6), retries=attempt)
            return answer
        except Exception as exc:  # noqa: BLE001 - mapped to an LLMError below
            err, wait = map_error(exc, ctx)
        if not err.retryable or attempt >= s.max_retries:
            err.retries = attempt  # type: ignore[attr-defined]
            raise err from None  # the SDK's exception may quote headers: keep it off the chain
        if wait is None:
            wait = s.retry_backoff_s * (2**attempt)
        await asyncio.sleep(max(0.0, min(wait, s.retry_max_wait_s)))
        attempt += 1


def read(completion: Any, s: LLMSettings, ctx: dict) -> dict:
    """The cacheable answer in an SDK completion (MalformedResponse, EmptyResponse: none)."""
    choices = getattr(completion, "choices", None)
    if not choices or getattr(choices[0], "message", None) is None:
        raise E.MalformedResponse(f"answer without choices: {str(completion)[:200]}", **ctx)
    raw = choices[0].message.content or ""
    text = strip_think(raw) if s.strip_think else raw
    calls = tool_calls_of(choices[0].message)
    if not text.strip() and not calls:  # an answer of tool calls only is not empty
        raise E.EmptyResponse(f"empty answer (finish_reason={choices[0].finish_reason})", **ctx)
    usage = getattr(completion, "usage", None)
    answer = {
        "raw_text": raw,
        "finish_reason": choices[0].finish_reason,
        "input_tokens": getattr(usage, "prompt_tokens", None),
        "output_tokens": getattr(usage, "completion_tokens", None),
        "model": getattr(completion, "model", None),
    }
    if calls:  # only then, so an answer without calls is cached and hashed as before
        answer["tool_calls"] = calls
    return answer


def tool_calls_of(message: Any) -> list[dict]:
    """The message's tool calls in the OpenAI wire shape ({"id", "type", "function": {"name", "arguments"}}),
    as JSON values (the cache stores them; tool_calls.py reads them)."""
    return [call.model_dump(mode="json", exclude_none=True) for call in getattr(message, "tool_calls", None) or []]


def map_error(exc: Exception, ctx: dict) -> tuple[E.LLMError, float | None]:
    """Our error for an SDK/parse failure, and the wait the provider asked for (if any)."""
    if isinstance(exc, E.LLMError):
        return exc, None
    if isinstance(exc, openai.APITimeoutError):
        return E.LLMTimeout(
            f"no answer within the timeout (llm.timeout=SECONDS raises it, per attempt): {exc}", **ctx
        ), None
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
        return kind(f"HTTP {status}: {message}", status=status, **ctx), retry_after(exc.response)
    if isinstance(exc, (ValueError, openai.APIResponseValidationError)):
        return E.MalformedResponse(f"answer is not a chat completion: {exc}", **ctx), None
    raise exc


def retry_after(response: Any) -> float | None:
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
