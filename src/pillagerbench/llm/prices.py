"""What an LLM call costs: USD per million input and output tokens, by provider and model.

The price comes from `llm.price.input_per_1m` and `llm.price.output_per_1m` when both are given
(an override: a preset or the command line), else from the price table of the pinned
`genai-prices` package (pydantic's maintained table of provider prices). Only the table the
package ships is read: its auto-update (`genai_prices.UpdatePrices`, which fetches a newer table
over the network) is never started, so a run never downloads anything. A newer table comes with a
newer pin.

The table is asked by provider: the preset's `provider` when the table knows a provider of exactly
that id (`openai`, `openrouter`, `anthropic`, ...), else the provider whose API address matches
`base_url` (e.g. `llm=openai_compatible llm.base_url=https://api.groq.com/openai/v1`). A local server
(llama.cpp, Ollama, vLLM, the fake provider) matches none: its price is unknown unless given. A
compatible proxy (`llm=openai_compatible`, e.g. LiteLLM in front of OpenAI) that matches no provider
is priced by the model's name when the table knows exactly one provider's model of that name
(`gpt-4o` → OpenAI's), the price's source saying so.

A model with no known price has an unknown cost (null in the ledger, never 0), and a dollar
budget (`llm.budget.max_cost_usd`) refuses to start until a price is given.

Tiered prices (a higher rate past some prompt size, e.g. 200k tokens) use the base tier: the
benchmark's prompts are far below any tier's start.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from importlib.metadata import PackageNotFoundError, version
from typing import Any

PRICE_TABLE = "genai-prices"
PROXIES = ("openai_compatible",)  # providers that stand in front of another's models: priced by model name


@dataclass(frozen=True)
class Price:
    """USD per million tokens (None: unknown) and where the figures came from."""

    input_per_1m: float | None
    output_per_1m: float | None
    source: str

    @property
    def known(self) -> bool:
        return self.input_per_1m is not None and self.output_per_1m is not None

    def cost(self, input_tokens: int | None, output_tokens: int | None) -> float | None:
        """USD of one call, or None when the price or the usage is unknown."""
        if not self.known or input_tokens is None or output_tokens is None:
            return None
        assert self.input_per_1m is not None and self.output_per_1m is not None
        return (input_tokens * self.input_per_1m + output_tokens * self.output_per_1m) / 1e6

    def to_dict(self) -> dict[str, Any]:
        return {"input_per_1m": self.input_per_1m, "output_per_1m": self.output_per_1m, "source": self.source}


def table_version() -> str:
    try:
        return f"{PRICE_TABLE} {version(PRICE_TABLE)}"
    except PackageNotFoundError:  # pragma: no cover - a declared dependency
        return PRICE_TABLE


def _flat(value: Any) -> float | None:
    """A price per million tokens: a Decimal, or a tiered price's base rate."""
    if value is None:
        return None
    return float(getattr(value, "base", value))


@functools.lru_cache(maxsize=256)
def table_price(provider: str, model: str, base_url: str = "") -> Price | None:
    """The price table's price for the model at this provider (or API address), None if it has none."""
    from datetime import datetime, timezone

    from genai_prices import data_snapshot  # the bundled table (about 0.4 s to load; never fetched)

    snapshot = data_snapshot.get_snapshot()
    match = data_snapshot.find_provider_by_id(snapshot.providers, provider)
    by_name = ""
    try:
        if match is not None and match.id == provider.lower():
            found, info = snapshot.find_provider_model(model, None, match.id, None)
        elif base_url and _serves(snapshot, base_url):
            found, info = snapshot.find_provider_model(model, None, None, base_url)
        elif provider in PROXIES:
            found, info = snapshot.find_provider_model(model, None, None, None)
            by_name = f" (by model name, through the {provider} proxy at {base_url or '?'})"
        else:
            return None
        prices = info.get_prices(datetime.now(timezone.utc))
    except LookupError:
        return None
    p_in, p_out = _flat(getattr(prices, "input_mtok", None)), _flat(getattr(prices, "output_mtok", None))
    if p_in is None or p_out is None:
        return None
    return Price(p_in, p_out, f"{table_version()}: {found.id} {info.id}{by_name}")


def _serves(snapshot: Any, base_url: str) -> bool:
    """Whether some provider of the table is known by this API address."""
    try:
        snapshot.find_provider("", None, base_url)
    except LookupError:
        return False
    return True


def resolve_price(
    provider: str, model: str, base_url: str, price_input: float | None, price_output: float | None
) -> Price:
    """The price of a call: the override when both figures are given, else the table's, else unknown."""
    if price_input is not None and price_output is not None:
        return Price(float(price_input), float(price_output), "llm.price")
    found = table_price(provider, model, base_url)
    if found is not None:
        return found
    return Price(None, None, f"unknown: {table_version()} has no price for {provider} model {model}")


def price_of(settings: Any) -> Price:
    """resolve_price for an LLMSettings."""
    s = settings
    provider, model = s.provider, s.model
    if provider == "inspect" and "/" in model:  # Inspect's name, `anthropic/claude-...`: priced by its parts
        provider, model = model.split("/", 1)
    return resolve_price(provider, model, s.base_url, s.price_input_per_1m, s.price_output_per_1m)


def price_problem(settings: Any, where: str = "llm") -> str | None:
    """One line when the settings cannot work for money: half a price given, or a dollar budget
    (`budget.max_cost_usd`) for a model whose price is unknown."""
    s = settings
    if (s.price_input_per_1m is None) != (s.price_output_per_1m is None):
        return f"{where}.price: give both input_per_1m and output_per_1m, or neither (then {PRICE_TABLE}'s are used)"
    limit = (s.budget or {}).get("max_cost_usd")
    if limit is None or price_of(s).known:
        return None
    return (
        f"{where}.budget.max_cost_usd={limit:g}: no price is known for {s.provider} model {s.model} "
        f"({table_version()} has none); give one with {where}.price.input_per_1m=USD "
        f"{where}.price.output_per_1m=USD (per million tokens)"
    )


def format_cost(known_usd: float, unpriced: int) -> str:
    """A total that says what it does not know: "$1.23", "≥ $1.23 (4 calls unpriced)", "unknown (4 calls unpriced)"."""
    if not unpriced:
        return f"${known_usd:.4f}" if known_usd < 1 else f"${known_usd:,.2f}"
    calls = f"{unpriced} call{'s' if unpriced != 1 else ''} unpriced"
    if known_usd <= 0:
        return f"unknown ({calls})"
    return f"≥ ${known_usd:.4f} ({calls})" if known_usd < 1 else f"≥ ${known_usd:,.2f} ({calls})"
