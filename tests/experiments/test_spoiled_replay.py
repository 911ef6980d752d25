"""Our faults are never a team's result. A series of cot against do_nothing on the real server, its LLM
provider (the fake one, pillagerbench.llm.fake_server) answering 503 for some episodes: the spoiled
episode is kept on disk, listed in the report's Failures table, in no score, and played again as the
next index so the series has its planned episodes; with the retries spent the series ends with fewer
used episodes and the report says so; a team's own budget spent stays its own (scored, not replayed).

The series play on the lockstep clock (docs/clock.md): what is tested is which episodes count, not
real time, and there lag cannot spoil an episode, so only the provider's outage spoils one here and the
counts are exact (a lagged episode is spoiled too and played again: tests/report/test_lagged.py and
tests/metrics/test_spoiled.py cover lag).
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from pillagerbench.config.compose import load_config
from pillagerbench.config.schema import RunConfig
from pillagerbench.experiments.series import run_series
from pillagerbench.llm.fake_server import FakeLLMServer, Rule
from pillagerbench.metrics.verified import load_runs
from pillagerbench.report.build import build_report
from pillagerbench.rundir import RunDir, SeriesSpec, faults, progress, spoiled
from tests.support.waiting_cot import ANSWER, overrides

PROVIDER = "provider unreachable"


def outage() -> Rule:
    return Rule(status=503, message="the provider is down")


def spec_of(fake: FakeLLMServer, episodes: int, retries: int, *extra: str) -> SeriesSpec:
    # every try counts here; waiting out an outage: tests/experiments/test_outage.py
    cfg = load_config(overrides(fake, episodes, f"retries={retries}", "outage_wait_s=0", *extra))
    return SeriesSpec(
        "run", 0, "run", "mushroom_war", "cot", "do_nothing", "cot", "do_nothing", episodes, 0, RunConfig.of(cfg)
    )


def by_provider(rec: dict) -> bool:
    return any(f.whose == "harness" and f.kind == PROVIDER for f in faults(rec))


async def play(tmp_path: Path, fake: FakeLLMServer, spec: SeriesSpec, outage_for: int | None) -> dict[int, dict]:
    """Play the series in tmp_path/run; the provider is down for its first `outage_for` episodes (None: all)."""
    fake.add(*([outage()] if outage_for != 0 else []), Rule(reply=ANSWER))
    played = []

    def after(rec) -> None:
        played.append(rec.episode)
        if outage_for is not None and len(played) >= outage_for:
            fake.reset()
            fake.add(Rule(reply=ANSWER))

    summary = await run_series(spec, tmp_path / "run", on_episode=after, say=lambda _: None)
    assert summary["played"] == len(played)
    return RunDir(tmp_path / "run").finished()


async def test_an_episode_without_the_provider_is_kept_listed_out_of_every_score_and_played_again(tmp_path):
    with FakeLLMServer() as fake:
        records = await play(tmp_path, fake, spec_of(fake, 2, 2), outage_for=1)
    assert by_provider(records[0]) and spoiled(records[0])  # the team played without its model
    assert [i for i, r in records.items() if by_provider(r)] == [0]
    assert sorted(records) == [0, 1, 2] and progress(records, 2, 2).used == 2  # replayed: planned count reached
    assert (tmp_path / "run" / "episode_000" / "timeline.json").exists()  # kept on disk

    runs = load_runs([tmp_path / "run"])
    assert 0 not in set(runs.episodes["episode"]) and len(runs.episodes) == 2
    assert 0 in set(runs.spoiled["episode"])
    assert any(f.episode == 0 and f.kind == PROVIDER and f.whose == "harness" for f in runs.faults)

    out = build_report([tmp_path / "run"], tmp_path / "report", with_replays=False)
    summary = pd.read_csv(tmp_path / "report" / "summary.csv")
    assert summary[["red", "episodes", "planned"]].values.tolist() == [["cot@fake-model", 2, 2]]
    used = runs.episodes
    assert summary["P"].iloc[0] == used["red_score"].mean()  # P over the used episodes only
    failures = pd.read_csv(tmp_path / "report" / "faults.csv")
    assert ((failures["episode"] == 0) & (failures["kind"] == PROVIDER)).any()
    assert any("spoiled on our side" in why for _, why in out["skipped"])


async def test_with_the_retries_spent_the_series_ends_with_fewer_episodes_and_says_so(tmp_path):
    with FakeLLMServer() as fake:
        records = await play(tmp_path, fake, spec_of(fake, 1, 1), outage_for=None)
    assert sorted(records) == [0, 1] and all(by_provider(r) for r in records.values())  # 1 + 1 try, no more
    done = progress(records, 1, 1)
    assert (done.complete, done.used, done.given_up) == (True, 0, 1)

    out = build_report([tmp_path / "run"], tmp_path / "report", with_replays=False)
    assert out["episodes"] == 0
    summary = pd.read_csv(tmp_path / "report" / "summary.csv")
    assert summary[["red", "episodes", "planned"]].values.tolist() == [["cot@fake-model", 0, 1]]  # 0 of 1: said
    assert any("1 of 1 planned episode(s) given up" in why and "0 of 1 used" in why for _, why in out["skipped"])
    assert pd.read_csv(tmp_path / "report" / "faults.csv")["kind"].tolist() == [PROVIDER, PROVIDER]


async def test_a_teams_own_budget_spent_is_scored_and_not_played_again(tmp_path):
    with FakeLLMServer() as fake:
        spec = spec_of(fake, 1, 2, "llm.budget.max_calls=0")  # every call refused by the team's own budget
        records = await play(tmp_path, fake, spec, outage_for=0)
    own = [f for f in faults(records[0]) if f.kind == "the team's budget spent"]
    assert own and own[0].whose == "team" and "BudgetExceeded" in own[0].what
    assert not any(by_provider(r) for r in records.values())
    assert sorted(records) == [0] and not spoiled(records[0])  # not played again
    runs = load_runs([tmp_path / "run"])
    assert list(runs.episodes["episode"]) == [0]  # the budget's episode is in the scores
