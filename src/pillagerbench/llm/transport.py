"""Where a request's answer comes from: the cache (the request's key and sample, a hit, a replay's miss)
or else the provider, through the official `openai` SDK (provider.py: our retries) or, for llm=inspect,
through Inspect (inspect_model.py). One `Transport` serves every client of a run, each team's and
each role's model: one connection to the provider, one cache. What a call costs and how it is
recorded is the client's (client.py): the transport answers a request and knows no team's books.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import openai

from . import errors as E
from . import provider
from .cache import LLMCache
from .settings import INSPECT, LLMSettings


@dataclass(frozen=True)
class Fetched:
    """A request's answer as the cache keeps it (provider.send's shape), and how it came."""

    response: dict[str, Any]
    retries: int  # the provider's tries after the first (0 for a cache hit)
    cache_hit: bool


class Transport:
    def __init__(self, cache: LLMCache, sdk: openai.AsyncOpenAI | None):
        self.cache = cache
        self.sdk = sdk  # None for llm=inspect, whose calls go through Inspect

    @classmethod
    def open(cls, settings: LLMSettings, cache: LLMCache | None = None) -> Transport:
        """The SDK's client for the provider the settings name (none for llm=inspect), and the cache
        (off when none is given)."""
        sdk = None
        if settings.provider != INSPECT:
            sdk = openai.AsyncOpenAI(
                api_key=settings.api_key(), base_url=settings.base_url, max_retries=0, timeout=settings.timeout
            )
        return cls(cache if cache is not None else LLMCache(None, "off"), sdk)

    def key(self, settings: LLMSettings, request: dict[str, Any]) -> tuple[str, int]:
        """The request's cache key and sample (the how-many-th time it is asked)."""
        return self.cache.key(settings.provider, request)

    async def fetch(
        self,
        s: LLMSettings,
        request: dict[str, Any],
        key: str,
        sample: int,
        *,
        role: str,
        team: str | None,
        ctx: dict[str, Any],
    ) -> Fetched:
        """The answer from the cache, else from the provider (then kept in the cache); in replay, a request
        not in the cache is a CacheMiss. The provider's failures are LLMErrors (provider.py)."""
        entry = self.cache.get(key) if self.cache.reads else None
        if entry is not None:
            return Fetched(entry["response"], 0, True)
        if self.cache.mode == "replay":
            raise E.CacheMiss(
                f"replay: request not in the cache {self.cache.dir} (key {key}, sample {sample})", key=key, **ctx
            )
        if self.sdk is None:  # llm=inspect
            from . import inspect_model

            response = await inspect_model.send(s, request, role=role, team=team, ctx=ctx)
        else:
            response = await provider.send(self.sdk, s, request, role=role, team=team, ctx=ctx)
        retries = response.pop("retries")
        self.cache.put(
            key, {"key": key, "sample": sample, "provider": s.provider, "request": request, "response": response}
        )
        return Fetched(response, retries, False)

    async def aclose(self) -> None:
        if self.sdk is not None:
            await self.sdk.close()
