"""The `inspect` provider: one request through Inspect's model API (`inspect_ai.model.get_model`), so
every provider Inspect has (Anthropic, Google, Bedrock, vLLM, its mock model ...) answers our teams,
with Inspect's own retries, cache and limits (llm=inspect; docs/inspect.md).

`llm.model` is Inspect's model name (`anthropic/claude-...`), or `eval` (EVAL_MODEL): inside an
Inspect evaluation, the model role named after the team's side (`--model-role red=...`) when one is
given, else the evaluation's model. The answer has the shape provider.send returns, so the client
(client.py) caches, budgets and records it as any other. Inspect's optional extra is imported only
here, and only when a call is made.

Tools (tool_calls.py): the request's OpenAI `tools`, `tool_choice`, assistant `tool_calls` and `tool`
messages become Inspect's ToolInfo, tool choice, ToolCall and ChatMessageTool; the answer's tool calls
come back in the OpenAI shape (arguments Inspect could not parse: its parse error, quoting them).
"""

from __future__ import annotations

import json
import re
import time
from collections.abc import Mapping
from typing import Any

from . import errors as E
from .parsing import strip_think
from .settings import EVAL_MODEL, LLMSettings

STOP_REASONS = {"max_tokens": "length", "model_length": "length"}  # Inspect's -> the OpenAI finish_reason we record


def one_line(text: object) -> str:
    """Inspect's message (rich markup, several lines) as one plain line."""
    return " ".join(re.sub(r"\[/?[a-z ]+\]", "", str(text)).split())


def _messages(request: dict[str, Any]) -> list[Any]:
    from inspect_ai.model import ChatMessageAssistant, ChatMessageSystem, ChatMessageTool, ChatMessageUser

    names: dict[str, str] = {}  # tool call id -> its function, for the tool message answering it
    out: list[Any] = []
    for m in request["messages"]:
        role, content = m.get("role", "user"), str(m.get("content") or "")
        if role in ("system", "developer"):
            out.append(ChatMessageSystem(content=content))
        elif role == "assistant":
            calls = [_inspect_call(call) for call in m.get("tool_calls") or []]
            names.update((call.id, call.function) for call in calls)
            out.append(ChatMessageAssistant(content=content, tool_calls=calls or None))
        elif role == "tool":
            call_id = str(m.get("tool_call_id") or "")
            out.append(ChatMessageTool(content=content, tool_call_id=call_id, function=names.get(call_id)))
        else:
            out.append(ChatMessageUser(content=content))
    return out


def _inspect_call(call: Mapping[str, Any]) -> Any:
    """An OpenAI tool call of the conversation as Inspect's ToolCall."""
    from inspect_ai.tool import ToolCall

    function = call.get("function") or {}
    raw = function.get("arguments") or "{}"
    try:
        arguments = json.loads(raw)
    except ValueError:
        arguments = None
    error = None if isinstance(arguments, dict) else f"arguments are not a JSON object: {raw}"
    return ToolCall(
        id=str(call.get("id") or ""),
        function=str(function.get("name") or ""),
        arguments=arguments if isinstance(arguments, dict) else {},
        parse_error=error,
    )


def _tools(request: dict[str, Any]) -> tuple[list[Any], Any]:
    """The request's OpenAI tools and tool_choice as Inspect's ToolInfo list and tool choice."""
    from inspect_ai.tool import ToolFunction, ToolInfo

    tools = []
    for tool in request.get("tools") or []:
        function = tool.get("function") or {}
        info = {k: function[k] for k in ("name", "description", "parameters") if function.get(k) is not None}
        tools.append(ToolInfo.model_validate({"description": "", **info}))
    choice = request.get("tool_choice")
    if isinstance(choice, Mapping):
        return tools, ToolFunction(name=choice["function"]["name"])
    return tools, {"required": "any"}.get(choice, choice) if choice is not None else None


def _wire_calls(calls: list[Any] | None) -> list[dict]:
    """Inspect's tool calls of an answer in the OpenAI shape (tool_calls.py reads them)."""
    return [
        {
            "id": call.id,
            "type": "function",
            "function": {"name": call.function, "arguments": call.parse_error or json.dumps(call.arguments)},
        }
        for call in calls or []
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
    try:  # a tool schema or tool call Inspect's types refuse (pydantic's ValidationError is a ValueError)
        messages, (tools, tool_choice) = _messages(request), _tools(request)
    except (ValueError, KeyError, TypeError) as exc:
        raise E.BadRequest(f"Inspect cannot take this request's tools: {one_line(exc)}", **ctx) from None
    try:
        model = _model(s, team)
        output = await model.generate(messages, tools=tools, tool_choice=tool_choice, config=_config(s, request))
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
    calls = _wire_calls(output.message.tool_calls if output.choices else None)
    if not text.strip() and not calls:
        raise E.EmptyResponse(f"empty answer (stop_reason={output.stop_reason})", **ctx)
    usage = output.usage
    return {
        **({"tool_calls": calls} if calls else {}),
        "raw_text": raw,
        "finish_reason": STOP_REASONS.get(output.stop_reason, output.stop_reason),
        "input_tokens": usage.input_tokens if usage else None,
        "output_tokens": usage.output_tokens if usage else None,
        "model": output.model or model.name,
        "latency_s": round(time.perf_counter() - t0, 6),
        "retries": 0,
    }
