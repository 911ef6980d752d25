"""Errors raised by the LLM layer. Every message is redacted: no API key ever appears in one."""

from __future__ import annotations

from .redact import redact


class LLMError(Exception):
    """Base class: a call to an LLM did not produce a usable answer."""

    retryable = False

    def __init__(
        self,
        message: str,
        *,
        status: int | None = None,
        role: str | None = None,
        team: str | None = None,
        model: str | None = None,
        provider: str | None = None,
    ):
        self.status = status
        self.role, self.team, self.model, self.provider = role, team, model, provider
        where = ", ".join(
            f"{k}={v}"
            for k, v in (("provider", provider), ("model", model), ("team", team), ("role", role), ("status", status))
            if v is not None
        )
        self.detail = redact(str(message))
        super().__init__(f"{self.detail} [{where}]" if where else self.detail)


class LLMConfigError(LLMError):
    """The LLM configuration cannot work (e.g. the key's environment variable is not set)."""


class AuthenticationFailed(LLMError):
    """401/403: wrong or missing key."""


class ModelNotFound(LLMError):
    """404: unknown model (or wrong base_url)."""


class BadRequest(LLMError):
    """400/422: the provider rejected the request itself."""


class RateLimited(LLMError):
    """429 after all retries."""

    retryable = True


class ProviderError(LLMError):
    """5xx or another unexpected status after all retries."""

    retryable = True


class LLMTimeout(LLMError):
    """No answer within the configured timeout, after all retries."""

    retryable = True


class LLMConnectionError(LLMError):
    """The provider could not be reached (connection refused, DNS, TLS), after all retries."""

    retryable = True


class MalformedResponse(LLMError):
    """The provider answered 200 with a body that is not a chat completion."""

    retryable = True


class EmptyResponse(LLMError):
    """The answer was empty (after stripping <think> blocks), after all retries."""

    retryable = True


class InvalidJSON(LLMError):
    """`complete_json`: no attempt produced valid JSON."""


class Cancelled(LLMError):
    """The caller cancelled the call (a deadline, the whistle); recorded in the ledger, then re-raised
    as asyncio.CancelledError."""


class BudgetExceeded(LLMError):
    """This team's per-episode budget (calls, tokens or cost) is used up; no request was sent."""


class CacheMiss(LLMError):
    """Cache mode `replay` and the request is not in the cache."""

    def __init__(self, message: str, *, key: str, **kw):
        self.key = key
        super().__init__(message, **kw)
