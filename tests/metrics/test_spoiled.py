"""Episodes spoiled on our side (rundir/faults.py) are in no score: the provider unreachable for a team
or the machine lagging keeps an episode out of P, S, D, W and the learning curve (the Failures and
lag tables list it), while a team's own failure (its budget spent, its code erring) is scored; and
which episode a series plays next (rundir/schedule.py), read from its records alone."""

from __future__ import annotations

import pandas as pd
import pytest

from pillagerbench.metrics.verified import load_runs
from pillagerbench.report.build import build_report
from pillagerbench.rundir import EpisodeRecord, faults, progress, spoiled
from tests.metrics.fake_runs import write_run

UNREACHABLE = "llm failed on all 1 call(s); last: LLMConnectionError: connection refused"
BUDGET = "llm failed on all 3 call(s); last: BudgetExceeded: budget of 0 calls per episode used up (0 used)"
OWN_CODE = "code error: ReferenceError: foo is not defined"


def test_our_faults_are_in_no_score_and_the_teams_own_are(tmp_path):
    run = write_run(
        tmp_path / "run",
        "mushroom_war",
        "cot",
        "do_nothing",
        [(3, 1), (0, 6), (1, 0), (0, 6), (5, 0)],
        problems={1: {"red": [UNREACHABLE]}, 2: {"red": [BUDGET]}, 4: {"red": [OWN_CODE]}},
        lagged={3: "server at 12.5 TPS (< 19)"},
    )
    runs = load_runs([run])
    assert list(runs.episodes["episode"]) == [0, 2, 4]  # the budget's and the code's episodes count
    assert list(runs.spoiled["episode"]) == [1, 3]
    assert list(runs.episodes["index"]) == [0, 1, 2]  # the learning curve's x has no hole

    build_report([run], tmp_path / "report", with_replays=False)
    summary = pd.read_csv(tmp_path / "report" / "summary.csv").iloc[0]
    assert (summary["episodes"], summary["planned"], summary["P"]) == (3, 5, pytest.approx(3.0))
    assert summary["W"] == pytest.approx(1.0)  # the two 0-6 losses were ours
    curve = pd.read_csv(tmp_path / "report" / "learning_curve.csv")
    assert list(curve["episode"]) == [0, 1, 2] and list(curve["D"]) == [2, 1, 5]
    failures = pd.read_csv(tmp_path / "report" / "faults.csv")
    ours = failures[failures["whose"] == "harness"]
    assert sorted(zip(ours["episode"], ours["kind"])) == [(1, "provider unreachable"), (3, "lagged")]
    theirs = failures[failures["whose"] == "team"]
    assert sorted(theirs["episode"]) == [2, 4]
    # each failure names its side's entrant (both for a fault of the whole episode, the lag)
    cot = runs.episodes["red"].iloc[0]  # the entrant's name (an LLM team of a config without a model: cot@?)
    assert dict(zip(failures["episode"], failures["entrant"])) == {
        1: cot,
        2: cot,
        3: f"{cot} vs do_nothing",
        4: cot,
    }
    assert list(pd.read_csv(tmp_path / "report" / "lagged.csv")["episode"]) == [3]


def record(**data) -> EpisodeRecord:
    return EpisodeRecord.from_dict({"episode": 0, **data})


OK, BAD = record(status="ok"), record(status="ok", lagged=True)


@pytest.mark.parametrize(
    "played, planned, retries, expected",
    [
        ([], 2, 2, (0, 0, 0, 0)),
        ([OK, OK], 2, 2, (2, 0, 0, None)),
        ([BAD, OK], 2, 2, (1, 1, 0, 2)),  # episode 0 spoiled: index 2 is played in its place
        ([BAD, BAD, BAD, OK], 2, 2, (1, 3, 1, None)),  # 1 + 2 tries spoiled: given up, the next one ends it
        ([BAD], 1, 0, (0, 1, 1, None)),  # retries=0: never played again, the series ends with none used
        ([OK, BAD, BAD, OK], 2, 2, (2, 2, 0, None)),
    ],
)
def test_the_next_episode_follows_from_the_records_alone(played, planned, retries, expected):
    records = dict(enumerate(played))
    done = progress(records, planned, retries)
    assert (done.used, done.spoiled, done.given_up, done.next) == expected


def test_a_budget_spent_is_the_teams_and_an_unreachable_provider_ours():
    assert spoiled(record(status="ok", problems={"red": [BUDGET]})) is None
    assert spoiled(record(status="ok", problems={"red": [UNREACHABLE]})) == "provider unreachable"
    assert spoiled(record(status="failed", error="PlayerError: bot died")) == "failed: a bot"
    assert spoiled(record(status="failed", error="BudgetExceeded: spent")) is None


def test_an_experiment_closes_with_what_our_faults_cost():
    from pillagerbench.experiments.runner import spoiled_lines

    calm, replayed, short = progress({0: OK}, 1), progress({0: BAD, 1: OK}, 1), progress({0: BAD}, 1, 0)
    assert spoiled_lines([calm]) == []
    (line,) = spoiled_lines([calm, replayed, short])
    assert line.startswith("2 episode(s) spoiled on our side (in no score")
    assert "; 1 planned episode(s) given up after every try: fewer episodes used" in line


def test_a_stalled_episode_is_ours_and_a_record_from_before_stalls_is_not_stalled():
    why = "lockstep: Ryn idle, neither run nor rested, and the world went on without it after the server's ..."
    rec = record(status="ok", stalled=True, stall_reason=why)
    assert spoiled(rec) == "stalled"
    (fault,) = faults(rec)
    assert (fault.whose, fault.kind, fault.side, fault.what) == ("harness", "stalled", "", why)
    before = record(status="ok", problems={"red": [why]})  # before stalls, the let-go was a side's problem
    assert not before.stalled and before.stall_reason is None and spoiled(before) is None
    assert EpisodeRecord.from_dict({**rec.to_dict(), "stall_reason": None}).stall_reason is None
