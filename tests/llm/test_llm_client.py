"""Requests and answers through the real fake server: headers, body switches, think-stripping."""

from pillagerbench.llm import LLMClient
from pillagerbench.llm.fake_server import Rule, count_tokens


async def test_answer_tokens_and_role_header(fake_llm, make_client):
    fake_llm.default_reply = "pong"
    client = make_client()
    answer = await client.complete("say pong", role="action")
    assert answer.text == "pong" and answer.finish_reason == "stop"
    assert answer.output_tokens == count_tokens("pong")
    assert answer.input_tokens == count_tokens("say pong") + 4
    assert answer.retries == 0 and not answer.cache_hit
    req = fake_llm.requests[-1]
    assert req.role == "action" and req.team == "red"
    assert req.body["model"] == "fake-model" and req.body["temperature"] == 0.3
    assert req.body["max_tokens"] == 512


async def test_rules_by_role_and_regex(fake_llm, make_client):
    fake_llm.add(Rule(role="critic", reply="critic says"), Rule(regex=r"mine \d+ logs", reply="mining"))
    client = make_client()
    assert (await client.complete("anything", role="critic")).text == "critic says"
    assert (await client.complete("please mine 3 logs", role="action")).text == "mining"
    assert (await client.complete("other", role="action")).text == "OK"


async def test_think_blocks_are_stripped(fake_llm, make_client):
    fake_llm.default_reply = "<think>\nlet me plan\n</think>\n\nattack the base"
    answer = await make_client().complete("go", role="tactics")
    assert answer.text == "attack the base"
    assert "<think>" in answer.raw_text


async def test_think_stripping_can_be_disabled(fake_llm, make_client):
    fake_llm.default_reply = "<think>x</think>y"
    answer = await make_client("llm.strip_think=false").complete("go", role="tactics")
    assert answer.text == "<think>x</think>y"


async def test_developer_role_and_reasoning_switches(fake_llm, make_client):
    client = make_client(
        "llm.system_role=developer", "llm.send_temperature=false", "llm.max_tokens_param=max_completion_tokens"
    )
    await client.complete([{"role": "system", "content": "rules"}, {"role": "user", "content": "hi"}], role="action")
    body = fake_llm.requests[-1].body
    assert [m["role"] for m in body["messages"]] == ["developer", "user"]
    assert "temperature" not in body
    assert body["max_completion_tokens"] == 512 and "max_tokens" not in body


async def test_extra_body_headers_and_call_params(fake_llm, make_client):
    client = make_client("+llm.extra_body.top_k=20", "+llm.extra_headers.X-Title=bench")
    await client.complete("hi", role="action", temperature=0.9, stop=["\n"], seed=7)
    req = fake_llm.requests[-1]
    assert req.body["top_k"] == 20 and req.body["stop"] == ["\n"] and req.body["seed"] == 7
    assert req.body["temperature"] == 0.9
    assert req.headers["x-title"] == "bench"


async def test_truncated_answer_is_returned_with_length(fake_llm, make_client):
    fake_llm.default_reply = "a long answer " * 20
    answer = await make_client().complete("hi", role="action", max_tokens=3)
    assert answer.truncated and answer.finish_reason == "length"
    assert answer.output_tokens == 3


async def test_teams_share_connection_but_not_team_name(fake_llm, make_client):
    client = make_client(team=None)
    blue = client.for_team("blue")
    await blue.complete("hi", role="opponent")
    assert fake_llm.requests[-1].team == "blue"
    assert isinstance(blue, LLMClient) and blue.ledger is client.ledger and blue.cache is client.cache


def test_strip_think_forms():
    from pillagerbench.llm.parsing import strip_think

    assert strip_think("a <think>x</think> b <think>y</think> c") == "a  b  c"
    assert strip_think("reasoning opened by the template</think>answer") == "answer"
    assert strip_think("answer <think>cut off while thinking") == "answer"
    assert strip_think("<THINK>x</THINK>ok") == "ok"
