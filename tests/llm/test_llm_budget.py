"""Per-team, per-episode budgets."""

import pytest

from pillagerbench.llm import Budget, BudgetExceeded, LLMError
from pillagerbench.llm.fake_server import count_tokens


async def test_call_budget_then_reset_episode(fake_llm, make_client, ledger_of):
    client = make_client("llm.budget.max_calls=2")
    await client.complete("a", role="action")
    await client.complete("b", role="action")
    with pytest.raises(BudgetExceeded, match="2 calls") as info:
        await client.complete("c", role="action")
    assert isinstance(info.value, LLMError) and info.value.team == "red"
    assert fake_llm.count == 2  # nothing was sent
    rec = ledger_of()[-1]
    assert rec["error_type"] == "BudgetExceeded" and "2 calls" in rec["error"]
    client.reset_episode()
    await client.complete("d", role="action")
    assert fake_llm.count == 3


async def test_output_token_budget(fake_llm, make_client):
    fake_llm.default_reply = "x" * 40  # 10 tokens
    client = make_client("llm.budget.max_output_tokens=15")
    await client.complete("a", role="action")
    await client.complete("b", role="action")  # 10 < 15: allowed, crosses the limit
    with pytest.raises(BudgetExceeded, match="output tokens"):
        await client.complete("c", role="action")


async def test_input_token_budget(fake_llm, make_client):
    client = make_client("llm.budget.max_input_tokens=5")
    await client.complete("a long prompt that is well over five tokens", role="action")
    with pytest.raises(BudgetExceeded, match="input tokens"):
        await client.complete("again", role="action")


async def test_cost_budget_and_ledger_cost(fake_llm, make_client, ledger_of):
    fake_llm.default_reply = "y" * 400  # 100 output tokens
    client = make_client("llm.price.input_per_1m=1000", "llm.price.output_per_1m=2000", "llm.budget.max_cost_usd=0.3")
    await client.complete("q", role="action")
    expected = ((count_tokens("q") + 4) * 1000 + 100 * 2000) / 1e6
    assert ledger_of()[0]["cost_usd"] == pytest.approx(expected)
    assert expected < 0.3 < 2 * expected
    await client.complete("q2", role="action")
    with pytest.raises(BudgetExceeded, match="cost"):
        await client.complete("q3", role="action")


async def test_budgets_are_per_team(fake_llm, make_client):
    base = make_client("llm.budget.max_calls=1", team=None)
    red, blue = base.for_team("red"), base.for_team("blue")
    await red.complete("a", role="action")
    with pytest.raises(BudgetExceeded):
        await red.complete("b", role="action")
    await blue.complete("c", role="action")
    custom = base.for_team("green", budget=Budget(max_calls=0))
    with pytest.raises(BudgetExceeded):
        await custom.complete("d", role="action")


def test_unknown_limit_is_rejected():
    with pytest.raises(ValueError, match="max_tokens"):
        Budget.from_limits({"max_tokens": 3})


async def test_concurrent_calls_cannot_overshoot_the_call_budget(fake_llm, make_client):
    import asyncio

    from pillagerbench.llm.fake_server import Rule

    fake_llm.add(Rule(delay=0.3))
    client = make_client("llm.budget.max_calls=2")
    results = await asyncio.gather(*(client.complete(f"q{i}", role="action") for i in range(3)), return_exceptions=True)
    assert sum(isinstance(r, BudgetExceeded) for r in results) == 1
    assert fake_llm.count == 2
