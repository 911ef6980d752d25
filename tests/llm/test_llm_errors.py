"""Bad input from providers: retries with backoff, timeouts, clear LLMError subclasses."""

import time

import pytest

from pillagerbench.llm import (
    AuthenticationFailed,
    EmptyResponse,
    InvalidJSON,
    LLMConfigError,
    LLMConnectionError,
    LLMError,
    LLMTimeout,
    MalformedResponse,
    ModelNotFound,
    ProviderError,
    RateLimited,
)
from pillagerbench.llm.fake_server import FakeLLMServer, Rule
from pillagerbench.llm.parsing import parse_json


async def test_429_waits_for_retry_after_then_succeeds(fake_llm, make_client, ledger_of):
    fake_llm.add(Rule(status=429, retry_after=0.3, times=1))
    client = make_client("llm.retry_backoff_s=0.001")
    start = time.perf_counter()
    answer = await client.complete("hi", role="action")
    assert time.perf_counter() - start >= 0.3  # the retry-after wait happened
    assert answer.text == "OK" and answer.retries == 1 and fake_llm.count == 2
    assert ledger_of()[-1]["retries"] == 1 and ledger_of()[-1]["error"] is None


async def test_429_until_retries_run_out(fake_llm, make_client, ledger_of):
    fake_llm.add(Rule(status=429, retry_after=0.01, message="slow down"))
    with pytest.raises(RateLimited, match="slow down") as info:
        await make_client("llm.max_retries=2").complete("hi", role="action")
    assert info.value.status == 429 and fake_llm.count == 3
    rec = ledger_of()[-1]
    assert rec["error_type"] == "RateLimited" and rec["retries"] == 2 and "slow down" in rec["error"]


async def test_5xx_exponential_backoff(fake_llm, make_client):
    fake_llm.add(Rule(status=500, times=2))
    client = make_client("llm.retry_backoff_s=0.1", "llm.max_retries=2")
    start = time.perf_counter()
    answer = await client.complete("hi", role="action")
    assert time.perf_counter() - start >= 0.1 + 0.2  # waited 0.1 then 0.2
    assert answer.retries == 2 and fake_llm.count == 3


async def test_5xx_exhausted_raises_provider_error(fake_llm, make_client, ledger_of):
    fake_llm.add(Rule(status=503, message="overloaded"))
    with pytest.raises(ProviderError, match="HTTP 503: overloaded"):
        await make_client().complete("hi", role="critic")
    assert fake_llm.count == 3  # fake preset: max_retries=2
    assert ledger_of()[-1]["error_type"] == "ProviderError" and ledger_of()[-1]["role"] == "critic"


async def test_wrong_key_is_401_without_retry(monkeypatch, make_client, ledger_of):
    monkeypatch.setenv("PB_TEST_KEY", "sk-wrong-0123456789")
    with FakeLLMServer(api_key="sk-right-9876543210") as server:
        client = make_client("llm.api_key_env=PB_TEST_KEY", url=server.url)
        with pytest.raises(AuthenticationFailed, match="Incorrect API key") as info:
            await client.complete("hi", role="action")
        assert server.count == 1
    assert "sk-wrong-0123456789" not in str(info.value)
    assert ledger_of()[-1]["error_type"] == "AuthenticationFailed"


async def test_unknown_model_is_404(make_client):
    with FakeLLMServer(models=["real-model"]) as server:
        with pytest.raises(ModelNotFound, match="does not exist"):
            await make_client(url=server.url).complete("hi", role="action")
        assert server.count == 1


async def test_connection_refused(make_client, closed_port, ledger_of):
    client = make_client("llm.max_retries=1", url=f"http://127.0.0.1:{closed_port}/v1")
    with pytest.raises(LLMConnectionError, match="cannot reach"):
        await client.complete("hi", role="action")
    rec = ledger_of()[-1]
    assert rec["error_type"] == "LLMConnectionError" and rec["retries"] == 1


async def test_timeout(fake_llm, make_client):
    fake_llm.add(Rule(delay=3.0))
    client = make_client("llm.timeout=0.3", "llm.max_retries=0")
    start = time.perf_counter()
    with pytest.raises(LLMTimeout):
        await client.complete("hi", role="action")
    assert time.perf_counter() - start < 2.5  # gave up well before the server answered


async def test_timeout_then_success(fake_llm, make_client):
    fake_llm.add(Rule(delay=1.5, times=1))
    answer = await make_client("llm.timeout=0.3", "llm.max_retries=1").complete("hi", role="action")
    assert answer.text == "OK" and answer.retries == 1


async def test_malformed_body_retried_then_error(fake_llm, make_client):
    fake_llm.add(Rule(malformed=True, times=1))
    assert (await make_client().complete("hi", role="action")).retries == 1
    fake_llm.add(Rule(malformed=True))
    with pytest.raises(MalformedResponse):
        await make_client().complete("hi", role="action")


async def test_empty_answer_retried_then_error(fake_llm, make_client):
    fake_llm.add(Rule(empty=True, times=1))
    assert (await make_client().complete("hi", role="action")).retries == 1
    fake_llm.add(Rule(empty=True))
    with pytest.raises(EmptyResponse):
        await make_client().complete("hi", role="action")
    fake_llm.rules[:] = [Rule(reply="<think>only thinking</think>")]
    with pytest.raises(EmptyResponse):
        await make_client().complete("hi", role="action")


async def test_missing_key_variable_names_it(monkeypatch, make_client):
    monkeypatch.delenv("PB_ABSENT_KEY", raising=False)
    with pytest.raises(LLMConfigError, match="PB_ABSENT_KEY"):
        make_client("llm.api_key_env=PB_ABSENT_KEY")


async def test_complete_json_reasks(fake_llm, make_client, ledger_of):
    fake_llm.add(
        Rule(reply="Sure! Here is the plan: attack", times=1), Rule(reply='```json\n{"plan": "attack", "n": 2}\n```')
    )
    value = await make_client().complete_json("plan as JSON", role="tactics")
    assert value == {"plan": "attack", "n": 2}
    assert fake_llm.count == 2
    second = fake_llm.requests[-1].messages
    assert second[1] == {"role": "assistant", "content": "Sure! Here is the plan: attack"}
    assert "JSON" in second[2]["content"]
    assert [r["role"] for r in ledger_of()] == ["tactics", "tactics"]


async def test_complete_json_gives_up(fake_llm, make_client):
    fake_llm.default_reply = "no json here"
    with pytest.raises(InvalidJSON, match="no json here"):
        await make_client().complete_json("plan", role="tactics", attempts=3)
    assert fake_llm.count == 3


def test_parse_json_variants():
    assert parse_json('{"a": 1}') == {"a": 1}
    assert parse_json('text before {"a": [1, 2]} after') == {"a": [1, 2]}
    assert parse_json("```\n[1, 2]\n```") == [1, 2]
    with pytest.raises(ValueError):
        parse_json('{"a": 1')


def test_every_error_is_an_llm_error():
    for kind in (
        AuthenticationFailed,
        EmptyResponse,
        InvalidJSON,
        LLMConfigError,
        LLMConnectionError,
        LLMTimeout,
        MalformedResponse,
        ModelNotFound,
        ProviderError,
        RateLimited,
    ):
        assert issubclass(kind, LLMError)
