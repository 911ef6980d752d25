"""What a run cost, in sight: `pillagerbench run` with an LLM team (the fake provider, priced on the
command line) ends with the team's calls, tokens and dollars per model, and the report's summary has
the cost and the cost per win of each red team; an unpriced model says so instead of a figure."""

from __future__ import annotations

import json
import re
from pathlib import Path

from pillagerbench.llm import read_ledger, summarize
from pillagerbench.llm.prices import format_cost
from pillagerbench.llm.spend import spend_lines
from pillagerbench.metrics import estimates as tables
from pillagerbench.metrics.verified import load_runs
from pillagerbench.rundir import RunDir, spoiled
from tests.support.cli import run_cli

PRICE = ["llm.price.input_per_1m=1000", "llm.price.output_per_1m=2000"]


def play(tmp_path: Path, url: str, *extra: str) -> tuple[str, Path]:
    run = tmp_path / "run"
    args = ["run", "red=cot", "blue=do_nothing", "llm=fake", f"llm.base_url={url}", "episode_length=5"]
    done = run_cli(tmp_path, *args, "display=plain", f"run_dir={run}", *extra, timeout=300)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    return done.stdout, run


def test_a_run_ends_with_what_each_team_spent_and_the_report_has_cost_per_win(tmp_path, fake_llm):
    out, run = play(tmp_path, fake_llm.url, *PRICE)
    stats = summarize(read_ledger(run))
    assert stats.calls > 0 and stats.cost_usd > 0 and not stats.unpriced
    # the expectation from the ledger's raw lines and the prices on the command line, not from summarize()
    calls = [json.loads(x) for x in (run / "llm_calls.jsonl").read_text().splitlines()]
    ok = [c for c in calls if not c.get("error")]
    tokens_in, tokens_out = sum(c["input_tokens"] for c in ok), sum(c["output_tokens"] for c in ok)
    assert stats.calls == len(calls) and (stats.input_tokens, stats.output_tokens) == (tokens_in, tokens_out)
    assert abs(stats.cost_usd - (tokens_in * 1000 + tokens_out * 2000) / 1e6) < 1e-9
    (line,) = [ln for ln in out.splitlines() if ln.startswith("LLM cost of ")]
    assert line == (
        f"LLM cost of cot@fake-model: {stats.calls} call(s) ({stats.errors} failed), {stats.input_tokens:,} tokens in, "
        f"{stats.output_tokens:,} out, {stats.cost_text()}"
    )
    runs = load_runs([run])
    row = tables.summary(runs.episodes, {}, runs.ledger).iloc[0]
    assert row["cost"] == stats.cost_text()
    records = RunDir(run).records()
    wins = sum(r.red_score > r.blue_score for r in records if not spoiled(r))  # a lagged one is replayed
    assert row["cost_per_win"] == (format_cost(stats.cost_usd / wins, 0) if wins else "– (no win)")


def test_an_unpriced_model_says_so_and_a_run_without_llm_team_prints_no_cost(tmp_path, fake_llm):
    out, run = play(tmp_path, fake_llm.url)
    (line,) = [ln for ln in out.splitlines() if ln.startswith("LLM cost of ")]
    assert re.fullmatch(
        r"LLM cost of cot@fake-model: \d+ call\(s\) \(0 failed\), [\d,]+ tokens in, [\d,]+ out, unknown \(\d+ calls? unpriced\)",
        line,
    )
    runs = load_runs([run])
    row = tables.summary(runs.episodes, {}, runs.ledger).iloc[0]
    assert row["cost"].startswith("unknown (") and row["cost_per_win"] in ("unknown", "– (no win)")
    assert spend_lines([(tmp_path / "nowhere" / "llm_calls.jsonl", {"red": "passive"})]) == []
