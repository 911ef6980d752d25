"""Preflight: before episode 0, one short request to each distinct provider + model + base URL a
run will use, so a missing key, an unreachable server or an unknown model stops the run with one
line instead of 150 episodes of zeros. `llm.preflight=false` skips it.

No ledger, no cache, no budget: the request always reaches the provider. One attempt, no retries.
An empty or truncated answer counts as reachable (the provider answered). `probe` sends the same
request during a run, to a provider that answered none of a team's calls (experiments/outage.py).
"""

from __future__ import annotations

import asyncio
import dataclasses
from collections.abc import Iterable
from typing import Any

from . import errors as E
from .client import LLMClient
from .settings import LLMSettings

PROMPT = "Reply with the single word: ok"

# error class -> what to do about it
FIXES: dict[type[E.LLMError], str] = {
    E.LLMConfigError: "set the variable (export NAME=...) or choose another preset with llm=...",
    E.AuthenticationFailed: "the key was refused: check the key in the variable llm.api_key_env names",
    E.ModelNotFound: "unknown model or wrong URL: check llm.model and llm.base_url",
    E.LLMConnectionError: "nothing answers there: start the model server or fix llm.base_url",
    E.LLMTimeout: "no answer in time: check the server, or raise llm.timeout",
    E.BadRequest: "the provider refused the request: check the llm.* switches for this model (docs/llm.md)",
}
OK_ANYWAY = (E.EmptyResponse,)
# the errors that are no answer: the provider could not be reached (refused, name not resolved), timed out,
# or failed with a 5xx, 429 or a body that is no answer; a series waits for it to answer (`probe`,
# experiments/outage.py). Any other error is the provider's answer (a refused key, an unknown model).
UNANSWERED: tuple[type[E.LLMError], ...] = (
    E.LLMConnectionError,
    E.LLMTimeout,
    E.ProviderError,
    E.RateLimited,
    E.MalformedResponse,
)


def where(s: LLMSettings) -> str:
    return f"{s.provider} model {s.model} at {s.base_url}"


async def _ask(settings: LLMSettings, role: str) -> None:
    """One short request: one attempt, at most 20 s, no budget (nor ledger or cache)."""
    quick = dataclasses.replace(settings, max_retries=0, timeout=min(settings.timeout, 20.0), budget={})
    async with LLMClient(quick, team=role) as client:
        await client.complete(PROMPT, role=role)


async def _check(settings: LLMSettings) -> str | None:
    try:
        await _ask(settings, "preflight")
    except OK_ANYWAY:
        return None
    except E.LLMError as exc:
        fix = next((f for cls, f in FIXES.items() if isinstance(exc, cls)), "see docs/troubleshooting.md")
        return f"LLM preflight failed for {where(settings)}: {exc.detail} ({fix}; llm.preflight=false skips this check)"
    return None


async def preflight(llm_configs: Iterable[Any]) -> list[str]:
    """One line per distinct provider/model/URL that does not answer; [] when all do. Configs whose
    `preflight` is false are skipped."""
    distinct: dict[tuple, LLMSettings] = {}
    problems: list[str] = []
    for cfg in llm_configs:
        try:
            s = LLMSettings.from_config(cfg)
        except E.LLMConfigError as exc:
            problems.append(f"LLM settings: {exc.detail}")
            continue
        if s.preflight:
            distinct.setdefault((s.provider, s.model, s.base_url), s)
    problems += [p for p in await asyncio.gather(*(_check(s) for s in distinct.values())) if p]
    return problems


async def probe(llm_config: Any) -> str | None:
    """The preflight's request to a provider that answered none of a team's calls (a series waiting out an
    outage, experiments/outage.py): a line naming it and its error when it does not answer (`UNANSWERED`),
    None when it answers, with an error of another kind too (waiting would not change a refused key)."""
    try:
        settings = LLMSettings.from_config(llm_config)
        await _ask(settings, "probe")
    except UNANSWERED as exc:
        return f"{where(settings)}: {type(exc).__name__}: {exc.detail}"
    except E.LLMError:
        return None
    return None
