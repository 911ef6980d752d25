"""The `inspect` provider: one request through Inspect's model API (`inspect_ai.model.get_model`), so
every provider Inspect has (Anthropic, Google, Bedrock, vLLM, its mock model ...) answers our teams,
with Inspect's own retries, cache and limits (llm=inspect; docs/inspect.md).

`llm.model` is Inspect's model name (`anthropic/claude-...`), or `eval` (EVAL_MODEL): inside an
Inspect evaluation, the model role named after the team's side (`--model-role red=...`) when one is
given, else the evaluation's model. The answer has the shape provider.send returns, so the client
(client.py) caches, budgets and records it as any other. Inspect's optional extra is imported only
here, and only when a call is made.
"""

from __future__ import annotations

import re
import time
from typing import Any

from . import errors as E
from .parsing import strip_think
from .settings import EVAL_MODEL, LLMSettings

STOP_REASONS = {"max_tokens": "length", "model_length": "length"}  # Inspect's -> the OpenAI finish_reason we record


def one_line(text: object) -> str:
    """Inspect's message (rich markup, several lines) as one plain line."""
    return " ".join(re.sub(r"\[/?[a-z ]+\]", "", str(text)).split())


def _messages(request: dict[str, Any]) -> list[Any]:
    from inspect_ai.model import ChatMessageAssistant, ChatMessageSystem, ChatMessageUser

    kinds = {"system": ChatMessageSystem, "developer": ChatMessageSystem, "assistant": ChatMessageAssistant}
    return [
        kinds.get(m.get("role", "user"), ChatMessageUser)(content=str(m.get("content") or ""))
        for m in request["messages"]
    ]


def _config(s: LLMSettings, request: dict[str, Any]) -> Any:
    from inspect_ai.model import GenerateConfig

    tokens = request.get(s.max_tokens_param)
    return GenerateConfig(temperature=request.get("temperature"), max_tokens=tokens, seed=request.get("seed"))


def _model(s: LLMSettings, team: str | None) -> Any:
    """Inspect's model for the team: inside an evaluation the side's model role (else the evaluation's
    model) when `llm.model` is `eval` or names it (that instance, with its own arguments and
    config); else Inspect's model by the name `llm.model` gives."""
    from inspect_ai.model import get_model
    from inspect_ai.model._model import active_model  # the evaluation's model, None outside one

    if active_model() is not None:
        ambient = get_model(role=team or None)
        if s.model in (EVAL_MODEL, str(ambient)):
            return ambient
    return get_model(None if s.model == EVAL_MODEL else s.model)


async def send(s: LLMSettings, request: dict[str, Any], *, role: str, team: str | None, ctx: dict) -> dict:
    """One generate() through Inspect; returns the cacheable answer plus `retries` (Inspect's own
    retries are not counted: 0). An Inspect limit reached (--token-limit, --message-limit, a cost
    limit) is our BudgetExceeded: the team stops asking, as when its own budget is spent."""
    from inspect_ai._util.error import PrerequisiteError
    from inspect_ai.util import LimitExceededError

    t0 = time.perf_counter()
    try:
        model = _model(s, team)
        output = await model.generate(_messages(request), config=_config(s, request))
    except LimitExceededError as exc:
        raise E.BudgetExceeded(f"Inspect's {exc.type} limit reached: {exc.message}", **ctx) from None
    except PrerequisiteError as exc:  # the provider's key or package missing
        raise E.LLMConfigError(f"Inspect cannot use llm.model={s.model}: {one_line(exc.message)}", **ctx) from None
    except ValueError as exc:  # an unknown model, or none given and none in the evaluation
        raise E.ModelNotFound(f"Inspect has no model for llm.model={s.model}: {exc}", **ctx) from None
    except Exception as exc:  # noqa: BLE001 - Inspect retried already; any failure left is the provider's
        raise E.ProviderError(f"Inspect model call failed: {type(exc).__name__}: {exc}", **ctx) from None
    if output.error:
        raise E.ProviderError(f"Inspect model error: {output.error}", **ctx)
    raw = output.completion or ""
    text = strip_think(raw) if s.strip_think else raw
    if not text.strip():
        raise E.EmptyResponse(f"empty answer (stop_reason={output.stop_reason})", **ctx)
    usage = output.usage
    return {
        "raw_text": raw,
        "finish_reason": STOP_REASONS.get(output.stop_reason, output.stop_reason),
        "input_tokens": usage.input_tokens if usage else None,
        "output_tokens": usage.output_tokens if usage else None,
        "model": output.model or model.name,
        "latency_s": round(time.perf_counter() - t0, 6),
        "retries": 0,
    }
