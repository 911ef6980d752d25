"""Prices by provider and model (llm/prices.py): the pinned genai-prices table, `llm.price` as an
override, unknown prices recorded as unknown costs, and a dollar budget that needs a price."""

import socket
from pathlib import Path

import pytest

from pillagerbench.config.compose import ConfigError, load_config
from pillagerbench.config.validate import check_run_config
from pillagerbench.llm import LLMClient, LLMConfigError, LLMSettings, summarize
from pillagerbench.llm.fake_server import count_tokens
from pillagerbench.llm.prices import format_cost, price_of, table_price
from tests.support.cli import run_cli

TABLE = "genai-prices 0.2.3"


def settings(provider: str, model: str, **kw) -> LLMSettings:
    return LLMSettings(provider=provider, model=model, **kw)


def test_table_prices_gpt_4o_gpt_4o_mini_and_an_unknown_model(monkeypatch):
    def no_network(*args, **kw):
        raise AssertionError("the price table must not touch the network")

    monkeypatch.setattr(socket.socket, "connect", no_network)
    table_price.cache_clear()
    big = price_of(settings("openai", "gpt-4o"))
    assert (big.input_per_1m, big.output_per_1m) == (2.5, 10.0)
    assert big.source == f"{TABLE}: openai gpt-4o"
    mini = price_of(settings("openai", "gpt-4o-mini"))
    assert (mini.input_per_1m, mini.output_per_1m) == (0.15, 0.6)
    routed = price_of(settings("openrouter", "openai/gpt-4o-mini", base_url="https://openrouter.ai/api/v1"))
    assert (routed.input_per_1m, routed.output_per_1m) == (0.15, 0.6)
    unknown = price_of(settings("openai", "gpt-nonexistent"))
    assert not unknown.known and unknown.cost(100, 100) is None
    assert unknown.source.startswith("unknown:") and "gpt-nonexistent" in unknown.source
    # a local server is never priced from the table, whatever its model is called
    for local in ("vllm", "ollama", "llamacpp", "fake"):
        assert not price_of(settings(local, "gpt-4o", base_url="http://127.0.0.1:8080/v1")).known
    # a compatible proxy (e.g. LiteLLM in front of OpenAI) is priced by the model's name, and says so
    proxy = price_of(settings("openai_compatible", "gpt-4o", base_url="http://127.0.0.1:4000/v1"))
    assert (proxy.input_per_1m, proxy.output_per_1m) == (2.5, 10.0)
    assert (
        proxy.source
        == f"{TABLE}: openai gpt-4o (by model name, through the openai_compatible proxy at http://127.0.0.1:4000/v1)"
    )
    assert not price_of(settings("openai_compatible", "local", base_url="http://127.0.0.1:8080/v1")).known
    # a compatible address the table knows is priced as that provider's
    groq = price_of(settings("openai_compatible", "llama-3.1-8b-instant", base_url="https://api.groq.com/openai/v1"))
    assert groq.known and groq.source.endswith("groq llama-3.1-8b-instant")
    # the preset's (or the command line's) price overrides the table
    over = price_of(settings("openai", "gpt-4o", price_input_per_1m=1.0, price_output_per_1m=2.0))
    assert (over.input_per_1m, over.output_per_1m, over.source) == (1.0, 2.0, "llm.price")


@pytest.mark.parametrize(("model", "p_in", "p_out"), [("gpt-4o", 2.5, 10.0), ("gpt-4o-mini", 0.15, 0.6)])
async def test_fake_providers_usage_priced_by_model_into_the_ledger(
    fake_llm, make_client, ledger_of, model, p_in, p_out
):
    fake_llm.default_reply = "z" * 400  # 100 output tokens
    # llm=openai's provider and model, pointed at the fake server (only the address differs)
    client = make_client("llm.provider=openai", f"llm.model={model}")
    answer = await client.complete("what does it cost", role="action")
    [rec] = ledger_of()
    tin, tout = count_tokens("what does it cost") + 4, 100
    assert (rec["input_tokens"], rec["output_tokens"]) == (tin, tout) == (answer.input_tokens, answer.output_tokens)
    assert rec["cost_usd"] == pytest.approx((tin * p_in + tout * p_out) / 1e6)
    assert rec["price"] == {"input_per_1m": p_in, "output_per_1m": p_out, "source": f"{TABLE}: openai {model}"}
    stats = summarize(ledger_of())
    assert stats.unpriced == 0 and stats.cost_usd == pytest.approx(rec["cost_usd"])
    assert client.budget.cost_usd == pytest.approx(rec["cost_usd"])


async def test_unknown_model_costs_unknown_not_zero(fake_llm, make_client, ledger_of):
    client = make_client()  # llm=fake: provider fake, model fake-model, in no price table
    await client.complete("a", role="action")
    await client.complete("b", role="action")
    records = ledger_of()
    assert [r["cost_usd"] for r in records] == [None, None]
    assert records[0]["price"]["input_per_1m"] is None and records[0]["price"]["source"].startswith("unknown:")
    stats = summarize(records)
    assert (stats.unpriced, stats.cost_usd) == (2, 0.0)
    assert stats.cost_text() == "unknown (2 calls unpriced)"
    assert client.budget.unpriced == 2 and client.budget.cost_usd == 0.0
    # mixed with priced calls: a lower bound that says so
    priced = make_client("llm.price.input_per_1m=1000", "llm.price.output_per_1m=1000")
    await priced.complete("c", role="action")
    mixed = summarize(ledger_of())
    assert mixed.unpriced == 2 and mixed.cost_usd > 0
    assert mixed.cost_text().startswith("≥ $") and mixed.cost_text().endswith("(2 calls unpriced)")
    assert format_cost(1.5, 0) == "$1.50"


def test_dollar_budget_with_an_unknown_price_refuses_to_start(fake_llm):
    base = ["llm=fake", f"llm.base_url={fake_llm.url}", "red=cot", "llm.budget.max_cost_usd=0.5"]
    with pytest.raises(ConfigError) as info:
        check_run_config(load_config(base))
    [line] = str(info.value).splitlines()
    assert "llm.budget.max_cost_usd=0.5" in line and "fake model fake-model" in line
    assert "llm.price.input_per_1m=" in line and "llm.price.output_per_1m=" in line
    # the client refuses too (library use)
    with pytest.raises(LLMConfigError, match="no price is known for fake model fake-model"):
        LLMClient.from_config(load_config(base))
    # with a price it starts
    check_run_config(load_config([*base, "llm.price.input_per_1m=1", "llm.price.output_per_1m=2"]))
    # a model the table prices needs none
    check_run_config(load_config([*base, "llm.provider=openai", "llm.model=gpt-4o"]))
    # half a price is refused
    with pytest.raises(ConfigError, match="give both input_per_1m and output_per_1m"):
        check_run_config(load_config([*base, "llm.price.input_per_1m=1"]))


def test_dollar_budget_refusal_from_the_command_line(tmp_path: Path):
    out = run_cli(tmp_path, "run", "red=cot", "llm=fake", "llm.budget.max_cost_usd=1", "llm.model=my-model")
    assert out.returncode == 2, out.stderr
    [line] = out.stderr.strip().splitlines()
    assert line.startswith("pillagerbench run: llm.budget.max_cost_usd=1: no price is known for fake model my-model")
    assert "llm.price.input_per_1m=USD llm.price.output_per_1m=USD" in line
    assert "Traceback" not in out.stderr and not (tmp_path / "runs").exists()
