"""Asking with tools (llm/tool_calls.py) through the real fake server: scripted tool calls parsed, the
tools on the wire, bad arguments kept (never raised), the ledger, the cache, the conversation going on;
and llm=inspect through Inspect's mock model."""

from __future__ import annotations

import importlib.util
from contextlib import asynccontextmanager
from dataclasses import dataclass

import pytest

from pillagerbench.llm import BudgetExceeded, CacheMiss
from pillagerbench.llm.fake_server import Rule
from pillagerbench.llm.tool_calls import ToolCall, ask_with_tools, tool_result

MINE = {
    "type": "function",
    "function": {
        "name": "mineBlock",
        "description": "Mine blocks of one kind near the bot.",
        "parameters": {
            "type": "object",
            "properties": {"name": {"type": "string"}, "count": {"type": "integer"}},
            "required": ["name", "count"],
        },
    },
}
CHAT = {
    "type": "function",
    "function": {
        "name": "chat",
        "description": "Say something.",
        "parameters": {"type": "object", "properties": {"text": {"type": "string"}}, "required": ["text"]},
    },
}
ASK = [{"role": "system", "content": "You play Minecraft."}, {"role": "user", "content": "Get wood."}]


async def test_tool_calls_are_parsed_and_the_tools_reach_the_server(fake_llm, make_client):
    fake_llm.add(
        Rule(
            tool_calls=[
                {"name": "mineBlock", "arguments": {"name": "oak_log", "count": 3}},
                {"name": "chat", "arguments": {"text": "on it"}, "id": "call_chat"},
            ]
        )
    )
    answer = await ask_with_tools(make_client(), ASK, tools=[MINE, CHAT], role="action")
    assert [c.name for c in answer.tool_calls] == ["mineBlock", "chat"]
    assert answer.tool_calls[0].arguments == {"name": "oak_log", "count": 3}
    assert answer.tool_calls[1] == ToolCall("call_chat", "chat", {"text": "on it"}, '{"text": "on it"}')
    assert answer.tool_calls[0].id and answer.tool_calls[0].id != "call_chat"
    assert answer.text == "" and answer.finish_reason == "tool_calls" and not answer.cache_hit
    assert answer.output_tokens and answer.input_tokens and answer.latency_s > 0 and answer.retries == 0
    message = answer.assistant_message
    assert message["role"] == "assistant" and message["content"] is None
    assert [c["function"]["name"] for c in message["tool_calls"]] == ["mineBlock", "chat"]
    req = fake_llm.requests[-1]
    assert req.tools == [MINE, CHAT] and req.messages == ASK and req.role == "action"
    assert "tool_choice" not in req.body  # none given: the provider's default


async def test_text_with_calls_tool_choice_and_tool_objects(fake_llm, make_client):
    @dataclass(frozen=True)
    class Spec:  # a team's ToolSpec: name, description, parameters
        name: str
        description: str
        parameters: dict

    fake_llm.add(Rule(reply="Mining now.", tool_calls=lambda body: [{"name": body["tools"][0]["function"]["name"]}]))
    spec = Spec("placeItem", "Place an item.", {"type": "object", "properties": {}})
    choice = {"type": "function", "function": {"name": "placeItem"}}
    answer = await ask_with_tools(make_client(), "go", tools=[spec], role="action", tool_choice=choice)
    assert answer.text == "Mining now." and answer.assistant_message["content"] == "Mining now."
    assert [(c.name, c.arguments) for c in answer.tool_calls] == [("placeItem", {})]
    body = fake_llm.requests[-1].body
    assert body["tools"] == [{"type": "function", "function": {"name": "placeItem", **_rest(spec)}}]
    assert body["tool_choice"] == choice


def _rest(spec) -> dict:
    return {"description": spec.description, "parameters": spec.parameters}


async def test_malformed_arguments_give_none_and_the_raw_text(fake_llm, make_client):
    fake_llm.add(
        Rule(
            tool_calls=[
                {"name": "mineBlock", "arguments": '{"name": "oak_log", "count": '},
                {"name": "chat", "arguments": '["not", "an", "object"]'},
            ]
        )
    )
    answer = await ask_with_tools(make_client(), ASK, tools=[MINE, CHAT], role="action")
    broken, listed = answer.tool_calls
    assert broken.arguments is None and broken.raw_arguments == '{"name": "oak_log", "count": '
    assert listed.arguments is None and listed.raw_arguments == '["not", "an", "object"]'
    assert answer.assistant_message["tool_calls"][0]["function"]["arguments"] == broken.raw_arguments


async def test_an_answer_without_calls_is_plain_text(fake_llm, make_client):
    fake_llm.default_reply = "I will not call anything."
    answer = await ask_with_tools(make_client(), ASK, tools=[MINE], role="action")
    assert answer.tool_calls == [] and answer.text == "I will not call anything." and answer.finish_reason == "stop"
    assert answer.assistant_message == {"role": "assistant", "content": "I will not call anything."}


async def test_the_ledger_records_the_call_with_its_tools_and_calls(fake_llm, make_client, ledger_of):
    fake_llm.add(Rule(tool_calls=[{"name": "mineBlock", "arguments": {"name": "oak_log", "count": 1}}]))
    client = make_client("llm_ledger.content=full")
    answer = await ask_with_tools(client, ASK, tools=[MINE], role="action")
    [rec] = ledger_of()
    assert (rec["role"], rec["team"], rec["model"], rec["error_type"]) == ("action", "red", "fake-model", None)
    assert rec["finish_reason"] == "tool_calls" and rec["cache_hit"] is False and rec["retries"] == 0
    assert rec["output_tokens"] == answer.output_tokens and rec["latency_s"] > 0
    assert rec["request"]["tools"] == [MINE]
    assert rec["response"]["tool_calls"] == answer.assistant_message["tool_calls"]


async def test_replay_answers_from_the_cache_and_other_tools_miss(fake_llm, make_client, tmp_path):
    fake_llm.add(Rule(tool_calls=[{"name": "mineBlock", "arguments": {"name": "oak_log", "count": 2}}]))
    cache_dir = tmp_path / "cache"
    first = make_client("llm_cache.mode=readwrite", f"llm_cache.dir={cache_dir}", run_dir=tmp_path / "r1")
    a = await ask_with_tools(first, ASK, tools=[MINE, CHAT], role="action")
    assert fake_llm.count == 1
    replay = make_client("llm_cache.mode=replay", f"llm_cache.dir={cache_dir}", run_dir=tmp_path / "r2")
    b = await ask_with_tools(replay, ASK, tools=[MINE, CHAT], role="action")
    assert b.cache_hit and fake_llm.count == 1
    assert b.tool_calls == a.tool_calls and b.assistant_message == a.assistant_message
    assert b.response.cache_key == a.response.cache_key
    with pytest.raises(CacheMiss):  # another tool list is another request
        await ask_with_tools(replay, ASK, tools=[MINE], role="action")
    with pytest.raises(CacheMiss):
        await ask_with_tools(replay, ASK, tools=[MINE, CHAT], role="action", tool_choice="required")
    assert fake_llm.count == 1


async def test_a_tool_result_continues_the_conversation(fake_llm, make_client):
    fake_llm.add(
        Rule(tool_calls=[{"name": "mineBlock", "arguments": {"name": "oak_log", "count": 3}}], times=1),
        Rule(match="mined 3 oak_log", reply="Done: 3 logs."),
    )
    client = make_client()
    messages = list(ASK)
    first = await ask_with_tools(client, messages, tools=[MINE], role="action")
    [call] = first.tool_calls
    messages += [first.assistant_message, tool_result(call, {"result": "mined 3 oak_log"})]
    second = await ask_with_tools(client, messages, tools=[MINE], role="action")
    assert second.text == "Done: 3 logs." and second.tool_calls == []
    sent = fake_llm.requests[-1].messages
    assert [m["role"] for m in sent] == ["system", "user", "assistant", "tool"]
    assert sent[2]["tool_calls"][0]["id"] == call.id and sent[2]["content"] is None
    assert sent[3] == {"role": "tool", "tool_call_id": call.id, "content": '{"result": "mined 3 oak_log"}'}


async def test_the_budget_and_the_thinking_hold_apply(fake_llm, make_client, ledger_of):
    fake_llm.add(Rule(tool_calls=[{"name": "chat", "arguments": {"text": "hi"}}]))
    client = make_client("llm.budget.max_calls=1")
    events: list = []

    @asynccontextmanager
    async def hold():
        events.append(("held", fake_llm.count))
        yield
        events.append(("released", fake_llm.count))

    async def charge(tokens: int) -> None:
        events.append(("charged", tokens))

    client.thinking.during_game(hold, charge)
    answer = await ask_with_tools(client, ASK, tools=[CHAT], role="action")
    assert events == [("held", 0), ("released", 1), ("charged", answer.output_tokens)]
    with pytest.raises(BudgetExceeded):
        await ask_with_tools(client, ASK, tools=[CHAT], role="action")
    assert fake_llm.count == 1 and [r["error_type"] for r in ledger_of()] == [None, "BudgetExceeded"]


@pytest.mark.skipif(importlib.util.find_spec("inspect_ai") is None, reason="the inspect extra is not installed")
async def test_llm_inspect_asks_with_tools(monkeypatch, tmp_path):
    import tiktoken
    from inspect_ai.model import ChatMessageTool, ModelOutput, get_model

    from pillagerbench.config.compose import load_config
    from pillagerbench.llm import LLMClient, inspect_model
    from tests.inspect_tasks.offline_tokens import ApproximateEncoding

    for name in ("get_encoding", "encoding_for_model"):  # the mock model counts tokens: offline, as tests/inspect_tasks
        monkeypatch.setattr(tiktoken, name, lambda _: ApproximateEncoding())
    seen: list = []

    def outputs():
        yield ModelOutput.for_tool_call("mockllm", "mineBlock", {"name": "oak_log", "count": 3}, tool_call_id="c1")
        yield ModelOutput.from_content("mockllm", "Done.")

    model = get_model("mockllm/model", custom_outputs=outputs())
    generate = model.generate

    async def spy(messages, **kw):
        seen.append((messages, kw))
        return await generate(messages, **kw)

    monkeypatch.setattr(model, "generate", spy)
    monkeypatch.setattr(inspect_model, "_model", lambda s, team: model)
    client = LLMClient.from_config(load_config(["llm=inspect", "llm.model=mockllm/model"]), run_dir=tmp_path)
    try:
        first = await ask_with_tools(client, ASK, tools=[MINE], role="action", tool_choice="required")
        [call] = first.tool_calls
        assert (call.id, call.name, call.arguments) == ("c1", "mineBlock", {"name": "oak_log", "count": 3})
        messages = [*ASK, first.assistant_message, tool_result(call, "mined 3")]
        second = await ask_with_tools(client, messages, tools=[MINE], role="action")
        assert second.text == "Done." and second.tool_calls == []
    finally:
        await client.aclose()
    tools, choice = seen[0][1]["tools"], seen[0][1]["tool_choice"]
    assert [t.name for t in tools] == ["mineBlock"] and tools[0].parameters.required == ["name", "count"]
    assert choice == "any"
    tool_message = seen[1][0][-1]
    assert isinstance(tool_message, ChatMessageTool) and tool_message.tool_call_id == "c1"
    assert tool_message.function == "mineBlock" and seen[1][0][-2].tool_calls[0].arguments["count"] == 3
