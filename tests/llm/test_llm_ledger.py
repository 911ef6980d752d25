"""The ledger: one record per call (failed ones too), its fields, and the metrics reader."""

import json

import pytest

from pillagerbench.llm import Ledger, ProviderError, read_ledger, summarize
from pillagerbench.llm.fake_server import Rule, count_tokens

FIELDS = {
    "ts",
    "team",
    "role",
    "provider",
    "model",
    "latency_s",
    "input_tokens",
    "output_tokens",
    "retries",
    "finish_reason",
    "cache_hit",
    "cache_key",
    "sample",
    "cost_usd",
    "error_type",
    "error",
}


async def test_record_fields_hash_mode(fake_llm, make_client, ledger_of):
    fake_llm.default_reply = "four score"
    await make_client().complete("hello there", role="critic")
    [rec] = ledger_of()
    assert FIELDS <= set(rec) and {"request_sha256", "response_sha256"} <= set(rec)
    assert "request" not in rec and "response" not in rec
    assert (rec["team"], rec["role"], rec["provider"], rec["model"]) == ("red", "critic", "fake", "fake-model")
    assert rec["input_tokens"] == count_tokens("hello there") + 4
    assert rec["output_tokens"] == count_tokens("four score")
    assert rec["finish_reason"] == "stop" and rec["retries"] == 0 and rec["cache_hit"] is False
    assert rec["error"] is None and rec["latency_s"] > 0
    assert len(rec["request_sha256"]) == 64


async def test_record_full_mode(fake_llm, make_client, ledger_of):
    fake_llm.default_reply = "full answer"
    await make_client("llm_ledger.content=full").complete("the question", role="cot")
    [rec] = ledger_of()
    assert rec["request"]["messages"] == [{"role": "user", "content": "the question"}]
    assert rec["response"]["raw_text"] == "full answer"


async def test_failed_calls_are_recorded(fake_llm, make_client, ledger_of):
    fake_llm.add(Rule(status=500, times=3))
    with pytest.raises(ProviderError):
        await make_client().complete("a", role="action")
    await make_client().complete("b", role="action")
    failed, ok = ledger_of()
    assert failed["error_type"] == "ProviderError" and failed["retries"] == 2
    assert failed["output_tokens"] is None and failed["response_sha256"] is None
    assert ok["error"] is None
    stats = summarize(ledger_of())
    assert (stats.calls, stats.ok, stats.errors, stats.retries) == (2, 1, 1, 2)


def test_summarize_metrics(tmp_path):
    ledger = Ledger(tmp_path / "run", content="hash")
    for team, lat, out in (("red", 1.0, 10), ("red", 3.0, 30), ("blue", 2.0, 50)):
        ledger.record(
            request={},
            response={},
            team=team,
            role="action",
            latency_s=lat,
            input_tokens=5,
            output_tokens=out,
            retries=0,
            cache_hit=False,
            error_type=None,
        )
    ledger.record(
        request={},
        response={},
        team="red",
        role="action",
        latency_s=0.001,
        orig_latency_s=2.0,
        input_tokens=5,
        output_tokens=20,
        retries=0,
        cache_hit=True,
        error_type=None,
    )
    ledger.record(
        request={},
        response=None,
        team="red",
        role="action",
        latency_s=9.0,
        input_tokens=None,
        output_tokens=None,
        retries=2,
        cache_hit=False,
        error_type="LLMTimeout",
        error="x",
    )
    ledger.close()
    records = list(read_ledger(tmp_path / "run"))
    red = summarize(records, team="red")
    assert (red.calls, red.ok, red.errors, red.cache_hits) == (4, 3, 1, 1)
    assert red.t_resp == pytest.approx((1.0 + 3.0 + 2.0) / 3)
    assert red.n_out == pytest.approx(20.0)
    assert red.r_tps == pytest.approx(60 / 6.0)
    both = summarize(records, original_latency=False)
    assert both.t_resp == pytest.approx((1.0 + 3.0 + 2.0 + 0.001) / 4)
    assert summarize(records, role="critic").t_resp is None


def test_reader_skips_a_torn_last_line(tmp_path):
    path = tmp_path / "llm_calls.jsonl"
    path.write_text(json.dumps({"role": "a"}) + "\n" + '{"role": "b", "lat')
    assert [r["role"] for r in read_ledger(path)] == ["a"]


async def test_a_cancelled_call_is_still_one_ledger_record(fake_llm, make_client, ledger_of):
    import asyncio

    from pillagerbench.llm.fake_server import Rule

    fake_llm.add(Rule(delay=1.0))
    client = make_client()
    with pytest.raises(asyncio.TimeoutError):
        await asyncio.wait_for(client.complete("slow", role="action"), 0.2)
    rec = ledger_of()[-1]
    assert rec["error_type"] == "Cancelled" and rec["role"] == "action"
    assert client.budget.in_flight == 0
