"""Asking an LLM until the answer is usable, with per-role model settings.

    llm = RoleLLM(ctx.llm, {"critic": {"temperature": 0.0}, "action": {"model": "big-model"}})
    result = await ask(llm, messages, role="critic", parse=parse_critique, attempts=3,
                       retry=lambda problem: f"That answer could not be used: {problem}. Answer again.")
    result.value      # what `parse` returned, or None
    result.record     # every attempt (answer or error, latency, tokens, problem) for the artefacts

`Chat` is what `ask` calls: an LLMClient, or a `RoleLLM`, which wraps one team's LLMClient. A role's overrides (`model`, `temperature`, `max_tokens`)
replace the team's `llm` settings for that role only; anything not overridden is the team's.
A role with its own model gets a client that shares the team's connection, ledger, cache and
budget (so budgets and the ledger stay per team), with the model swapped in.

`ask` sends the messages; when `parse` raises ValueError (the reason is its message) the answer
and a retry note are appended to the conversation and the model is asked again, up to `attempts`
calls. An LLMError ends the asking at once (the client has already retried what can be retried);
`BudgetExceeded` is reported as such so a team can stop calling for the rest of the episode.
With `deadline` (the episode's `Whistle`: a TeamContext) no call starts after the whistle, and on the
real clock a call still running then is abandoned (on the lockstep clock the world waits for it).
"""

from __future__ import annotations

import asyncio
import dataclasses
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, Generic, Protocol, TypeVar

from pillagerbench.llm import BudgetExceeded, LLMClient, LLMError, LLMResponse
from pillagerbench.llm.client import Messages

ROLE_KEYS = ("model", "temperature", "max_tokens")

T = TypeVar("T")


class Whistle(Protocol):
    """When the game ends, as a team's calls see it (a TeamContext)."""

    def time_left(self) -> float: ...  # game seconds to the whistle

    def wall_limit(self) -> float | None: ...  # how long a call may take on the wall clock (None: the world waits)


class Chat(Protocol):
    """What `ask` calls for an answer: an LLMClient, or a RoleLLM (per-role settings over one)."""

    async def complete(self, messages: Messages, *, role: str) -> LLMResponse: ...


def role_settings(roles: Mapping[str, Mapping[str, Any] | None] | None) -> dict[str, dict[str, Any]]:
    """Each role's overrides without the unset ones; ValueError for a setting not in ROLE_KEYS."""
    out: dict[str, dict[str, Any]] = {}
    for role, over in (roles or {}).items():
        over = dict(over or {})
        unknown = sorted(set(over) - set(ROLE_KEYS))
        if unknown:
            raise ValueError(f"role {role!r}: unknown setting(s) {unknown}; valid: {list(ROLE_KEYS)}")
        out[role] = {k: v for k, v in over.items() if v is not None}
    return out


class RoleLLM:
    """One team's LLM client with per-role overrides of model, temperature and max_tokens."""

    def __init__(self, client: LLMClient, roles: Mapping[str, Mapping[str, Any] | None] | None = None):
        self.client = client
        self.roles = role_settings(roles)
        self._clients: dict[str, LLMClient] = {}

    def client_for(self, role: str) -> LLMClient:
        model = self.roles.get(role, {}).get("model")
        if model is None or model == self.client.settings.model:
            return self.client
        if model not in self._clients:
            base = self.client
            self._clients[model] = LLMClient(
                dataclasses.replace(base.settings, model=str(model)),
                team=base.team,
                ledger=base.ledger,
                transport=base.transport,
                budget=base.budget,
                thinking=base.thinking,
            )
        return self._clients[model]

    def settings_for(self, role: str) -> dict[str, Any]:
        """The effective model/temperature/max_tokens of a role (for the record)."""
        s = self.client.settings
        out: dict[str, Any] = {"model": s.model, "temperature": s.temperature, "max_tokens": s.max_tokens}
        out.update(self.roles.get(role, {}))
        return out

    async def complete(self, messages: Messages, *, role: str, **kw: float | int | str | None) -> LLMResponse:
        over = self.roles.get(role, {})
        for key in ("temperature", "max_tokens"):
            if key in over and key not in kw:
                kw[key] = over[key]
        return await self.client_for(role).complete(messages, role=role, **kw)


@dataclass
class Asked(Generic[T]):
    """The outcome of `ask`: the parsed value (or None) and what happened on the way."""

    value: T | None = None
    attempts: list[dict] = field(default_factory=list)
    messages: list[dict] = field(default_factory=list)
    error: str | None = None  # why there is no value (last problem or the LLM error)
    budget_exceeded: bool = False
    llm_failed: bool = False  # an LLMError (not a bad answer) ended the asking
    out_of_time: bool = False

    @property
    def ok(self) -> bool:
        return self.value is not None

    @property
    def record(self) -> dict:
        return {"ok": self.ok, "error": self.error, "attempts": self.attempts, "messages": self.messages}


async def ask(
    llm: Chat | None,
    messages: list[dict],
    *,
    role: str,
    parse: Callable[[LLMResponse], T],
    attempts: int = 3,
    retry: Callable[[str], str] | None = None,
    deadline: Whistle | None = None,
) -> Asked[T]:
    """Call until `parse(answer)` returns a value (it raises ValueError with the problem otherwise)."""
    out: Asked[T] = Asked(messages=list(messages))
    if llm is None:
        out.error, out.llm_failed = "no LLM client", True
        return out
    msgs = list(messages)
    for n in range(max(1, attempts)):
        if deadline is not None and deadline.time_left() <= 0:
            out.error, out.out_of_time = out.error or "no time left for another call", True
            break
        left = None if deadline is None else deadline.wall_limit()
        t0 = time.monotonic()
        try:
            call = llm.complete(msgs, role=role)
            answer = await (call if left is None else asyncio.wait_for(call, timeout=left))
        except asyncio.TimeoutError:
            out.attempts.append(
                {"error": "the game ended before the answer came", "latency_s": round(time.monotonic() - t0, 3)}
            )
            out.error, out.out_of_time = "the game ended before the answer came", True
            break
        except LLMError as exc:
            out.attempts.append({"error": f"{type(exc).__name__}: {exc}", "latency_s": round(time.monotonic() - t0, 3)})
            out.error, out.llm_failed = f"{type(exc).__name__}: {exc}", True
            out.budget_exceeded = isinstance(exc, BudgetExceeded)
            break
        entry = {
            "answer": answer.text,
            "finish_reason": answer.finish_reason,
            "latency_s": answer.latency_s,
            "input_tokens": answer.input_tokens,
            "output_tokens": answer.output_tokens,
        }
        out.attempts.append(entry)
        try:
            out.value = parse(answer)
        except ValueError as exc:
            problem = str(exc)
            if answer.truncated:
                problem += " (the answer was cut off by the token limit: be shorter)"
            entry["problem"] = out.error = problem
            if n + 1 < attempts:
                note = retry(problem) if retry else f"Your answer could not be used: {problem}. Answer again."
                msgs = msgs + [{"role": "assistant", "content": answer.text}, {"role": "user", "content": note}]
                out.messages = list(msgs)
            continue
        out.error = None
        break
    return out
