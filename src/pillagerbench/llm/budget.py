"""Per-team, per-episode LLM budgets: calls, input tokens, output tokens and cost (USD).

`check()` runs before every call and raises BudgetExceeded once any limit has been reached, so
the call that crosses a token or cost limit still completes and the next one is refused.
Cache hits are charged like real calls (with the tokens the answer originally took), so a
replayed episode runs out of budget at the same point as the original. A call whose cost is
unknown (no price for the model, llm/prices.py, or no usage reported) adds nothing to `cost_usd`
and is counted in `unpriced`; a cost limit with an unknown price is refused before the run
(prices.price_problem), so it cannot silently never trip.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from .errors import BudgetExceeded

_OWN_PRICE: Any = object()
LIMITS = ("max_calls", "max_input_tokens", "max_output_tokens", "max_cost_usd")


@dataclass
class Budget:
    max_calls: int | None = None
    max_input_tokens: int | None = None
    max_output_tokens: int | None = None
    max_cost_usd: float | None = None
    price_input_per_1m: float | None = None  # None: unknown (costs are then unknown too)
    price_output_per_1m: float | None = None
    calls: int = 0
    input_tokens: int = 0
    output_tokens: int = 0
    cost_usd: float = 0.0  # of the calls whose cost is known
    unpriced: int = 0  # calls whose cost is unknown
    in_flight: int = 0  # calls checked and not finished: they count against max_calls
    failed: int = 0  # calls that raised an LLMError this episode (not counted in `calls`)
    last_error: str | None = None

    @classmethod
    def from_limits(
        cls,
        limits: Mapping[str, Any] | None,
        price_input_per_1m: float | None = None,
        price_output_per_1m: float | None = None,
    ) -> Budget:
        limits = dict(limits or {})
        unknown = sorted(set(limits) - set(LIMITS))
        if unknown:
            raise ValueError(f"unknown budget limits {unknown}; valid: {list(LIMITS)}")
        return cls(
            **{k: v for k, v in limits.items() if v is not None},
            price_input_per_1m=None if price_input_per_1m is None else float(price_input_per_1m),
            price_output_per_1m=None if price_output_per_1m is None else float(price_output_per_1m),
        )

    def cost(self, input_tokens: int | None, output_tokens: int | None) -> float | None:
        """USD of one call; None when the price or the usage is unknown."""
        if self.price_input_per_1m is None or self.price_output_per_1m is None:
            return None
        if input_tokens is None or output_tokens is None:
            return None
        return (input_tokens * self.price_input_per_1m + output_tokens * self.price_output_per_1m) / 1e6

    def exceeded(self) -> str | None:
        """Why no further call is allowed, or None."""
        for used, limit, what in (
            (self.calls + self.in_flight, self.max_calls, "calls"),
            (self.input_tokens, self.max_input_tokens, "input tokens"),
            (self.output_tokens, self.max_output_tokens, "output tokens"),
            (self.cost_usd, self.max_cost_usd, "cost (USD)"),
        ):
            if limit is not None and used >= limit:
                return f"budget of {limit} {what} per episode used up ({used:g} used)"
        return None

    def check(self, **context: Any) -> None:
        reason = self.exceeded()
        if reason is not None:
            raise BudgetExceeded(reason, **context)

    def reserve(self, **context: Any) -> None:
        """check(), then hold a call slot until release(): concurrent calls cannot overshoot max_calls."""
        self.check(**context)
        self.in_flight += 1

    def release(self) -> None:
        self.in_flight = max(0, self.in_flight - 1)

    def charge(self, input_tokens: int | None, output_tokens: int | None, cost: Any = _OWN_PRICE) -> float | None:
        """Count one call; returns its cost (None: unknown). `cost` given (the client's, from its
        price) is used as it is; by default it comes from this budget's own prices."""
        if cost is _OWN_PRICE:
            cost = self.cost(input_tokens, output_tokens)
        self.calls += 1
        self.input_tokens += input_tokens or 0
        self.output_tokens += output_tokens or 0
        if cost is None:
            self.unpriced += 1
        else:
            self.cost_usd += cost
        return cost

    def note_failure(self, error: Exception) -> None:
        self.failed += 1
        self.last_error = f"{type(error).__name__}: {getattr(error, 'detail', error)}"

    def problem(self) -> str | None:
        """A line when every call of the episode failed (the team played without its model)."""
        if self.failed and not self.calls:
            return f"llm failed on all {self.failed} call(s); last: {self.last_error}"
        return None

    def reset(self) -> None:
        self.calls = self.input_tokens = self.output_tokens = self.in_flight = self.failed = self.unpriced = 0
        self.cost_usd = 0.0
        self.last_error = None
