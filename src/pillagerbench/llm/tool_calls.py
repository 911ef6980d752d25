"""Asking with function calling: the OpenAI `tools` of a chat completion, through the one client.

    from pillagerbench.llm.tool_calls import ask_with_tools, tool_result

    tools = [{"type": "function", "function": {"name": "mineBlock", "description": "...",
              "parameters": {"type": "object", "properties": {...}, "required": [...]}}}]
    answer = await ask_with_tools(red, messages, tools=tools, role="action")
    messages.append(answer.assistant_message)            # the assistant's turn, its tool_calls included
    for call in answer.tool_calls:                       # call.name, call.arguments (None: not JSON)
        messages.append(tool_result(call, run(call)))    # {"role": "tool", "tool_call_id": ..., "content": ...}
    answer = await ask_with_tools(red, messages, tools=tools, role="action")   # the conversation goes on

It is `LLMClient.complete` with `tools` (and `tool_choice`) in the request body, so everything a call
has holds: the thinking hold, the budget, the cache (the tools are part of the request, hence of its
key), the provider's retries and LLMErrors, one ledger line per call (the tools in its request, the
calls in its response). A bad answer never raises here: arguments that are not a JSON object give
`arguments=None` with the text in `raw_arguments`. A tool may also be given as any object with
`name`, `description` and `parameters` (a JSON schema), e.g. a team's ToolSpec.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from .client import LLMClient, LLMResponse, Messages


@dataclass(frozen=True)
class ToolCall:
    id: str  # the provider's id: a tool message answering this call gives it as tool_call_id
    name: str
    arguments: dict[str, Any] | None  # None when raw_arguments is not a JSON object
    raw_arguments: str  # the arguments as the model wrote them


@dataclass(frozen=True)
class ToolAnswer:
    text: str  # the answer's text (<think> removed); often empty when it calls tools
    tool_calls: list[ToolCall]
    assistant_message: dict[str, Any]  # to append to the conversation (OpenAI shape, tool_calls included)
    response: LLMResponse  # the call as `complete` returns it

    @property
    def finish_reason(self) -> str | None:
        return self.response.finish_reason  # "tool_calls" when the model called tools

    @property
    def input_tokens(self) -> int | None:
        return self.response.input_tokens

    @property
    def output_tokens(self) -> int | None:
        return self.response.output_tokens

    @property
    def latency_s(self) -> float:
        return self.response.latency_s

    @property
    def retries(self) -> int:
        return self.response.retries

    @property
    def cache_hit(self) -> bool:
        return self.response.cache_hit

    @property
    def truncated(self) -> bool:
        return self.response.truncated


def as_tool(tool: Any) -> dict[str, Any]:
    """A tool in the OpenAI shape: a mapping as given, else built from `name`, `description`, `parameters`."""
    if isinstance(tool, Mapping):
        return dict(tool)
    function = {"name": tool.name, "description": tool.description, "parameters": dict(tool.parameters)}
    return {"type": "function", "function": function}


def parse_call(call: Mapping[str, Any]) -> ToolCall:
    """One wire tool call as a ToolCall; never raises (a custom tool's input counts as its arguments)."""
    function = call.get("function") or call.get("custom") or {}
    raw = function.get("arguments", function.get("input"))
    raw = raw if isinstance(raw, str) else json.dumps(raw)
    try:
        value = json.loads(raw)
    except (ValueError, RecursionError):  # not JSON, or nested past what json reads
        value = None
    arguments = value if isinstance(value, dict) else None
    return ToolCall(
        id=str(call.get("id") or ""), name=str(function.get("name") or ""), arguments=arguments, raw_arguments=raw
    )


def assistant_message(response: LLMResponse) -> dict[str, Any]:
    """The assistant's turn to append to the conversation: its text (None when it only calls tools) and
    its tool calls as the provider sent them."""
    message: dict[str, Any] = {"role": "assistant", "content": response.text or None}
    if response.tool_calls:
        message["tool_calls"] = [dict(call) for call in response.tool_calls]
    elif message["content"] is None:
        message["content"] = ""
    return message


def tool_result(call: ToolCall | str, content: Any) -> dict[str, Any]:
    """The tool message answering `call` (a ToolCall or its id); content not a string is sent as JSON."""
    text = content if isinstance(content, str) else json.dumps(content, ensure_ascii=False)
    return {"role": "tool", "tool_call_id": call.id if isinstance(call, ToolCall) else call, "content": text}


async def ask_with_tools(
    client: LLMClient,
    messages: Messages,
    *,
    tools: Sequence[Any],
    role: str,
    tool_choice: str | Mapping[str, Any] | None = None,
    **params: Any,
) -> ToolAnswer:
    """One chat completion offering `tools` (OpenAI shape, or objects with name/description/parameters).
    `tool_choice`: "auto", "none", "required" or {"type": "function", "function": {"name": ...}} (None: the
    provider's default). `params` as for `complete` (temperature, max_tokens, seed, parallel_tool_calls, ...).
    Raises what `complete` raises (LLMError subclasses); never for the content of an answer."""
    offered = [as_tool(tool) for tool in tools] or None  # no tools: a plain call (an empty list is refused)
    choice = dict(tool_choice) if isinstance(tool_choice, Mapping) else tool_choice
    response = await client.complete(messages, role=role, tools=offered, tool_choice=choice, **params)
    return ToolAnswer(
        text=response.text,
        tool_calls=[parse_call(call) for call in response.tool_calls],
        assistant_message=assistant_message(response),
        response=response,
    )
