"""`inspect_ai.eval()` in-process plays real episodes on our server: the log's sample, its scores (our
report's numbers), its transcript with the code each player ran; model roles make two LLM teams; a
token limit stops a team as its own budget does."""

from __future__ import annotations

import json
import math
from pathlib import Path

from inspect_ai.log import read_eval_log, resolve_sample_attachments

from pillagerbench.metrics.calibration import resolve
from pillagerbench.metrics.estimates import pairings
from pillagerbench.metrics.runs import read_runs
from pillagerbench.rundir import RunDir, faults, spoiled
from tests.inspect_tasks.conftest import PROGRAM, mock_model, run_eval


def info_events(sample) -> list[dict]:
    return [e.data for e in sample.events if e.event == "info" and isinstance(e.data, dict) and "episode" in e.data]


def test_model_against_model_plays_and_scores_as_the_report(tmp_path: Path) -> None:
    log = run_eval(
        tmp_path,
        {"opponents": "passive"},
        model_roles={"red": mock_model(), "blue": mock_model()},
    )
    assert log.status == "success", log.error
    sample = resolve_sample_attachments(read_eval_log(log.location).samples[0])
    run_dir = Path(sample.metadata["run_dir"])
    records = RunDir(run_dir).records()
    assert len(records) == 1 and records[0].status == "ok"
    # model against model: both sides are the LLM team, each asking its own role's model
    assert (records[0].red_entrant.team, records[0].blue_entrant.team) == ("cot", "cot")
    assert records[0].red_entrant.label == "cot@mockllm/model"
    calls = [json.loads(line) for line in (run_dir / "llm_calls.jsonl").read_text().splitlines()]
    assert {c["team"] for c in calls if not c["error_type"]} == {"red", "blue"}
    # the transcript: every prompt and answer (Inspect's model events), and the code each player ran
    assert sum(e.event == "model" for e in sample.events) == len(calls)
    [episode] = info_events(sample)
    programs = episode["code"]["red"]["cot.json"]["programs"]
    assert programs and all(PROGRAM.splitlines()[1].strip() in p["code"] for p in programs.values())
    assert episode["runs"] and episode["timeline"][-1]["t"] == 20
    assert episode["replay"].startswith("file://") and episode["replay"].endswith("replay.html")
    # the scores are the report's for the same episodes (red's pairing row)
    values = sample.scores["series_score"].value
    runs = read_runs([run_dir])
    row = pairings(runs.episodes, resolve(runs, fallback=True)[0]).iloc[0]
    for name, col in (("points", "P"), ("dominance", "D"), ("win", "W"), ("sabotage", "S")):
        assert math.isclose(values[name], row[col], abs_tol=1e-9) or (math.isnan(values[name]) and math.isnan(row[col]))
    # and the task's metrics are Inspect's over the samples (one sample here: its values)
    metrics = {s.name: s.metrics for s in log.results.scores}
    assert metrics["points"]["mean"].value == values["points"] and "stderr" in metrics["win"]
    assert math.isnan(values["sabotage"])  # against cot: σ_blue unknown (the report's "–"), left out of the mean
    assert math.isnan(metrics["sabotage"]["pillagerbench/known_mean"].value)


def test_token_limit_stops_the_team_as_its_budget_does(tmp_path: Path) -> None:
    # Inspect refuses the call that crosses --token-limit (its answer discarded); the team sees our
    # BudgetExceeded, as when its own budget is spent: it plays on without its model, and the
    # episode is the team's (it counts), not one spoiled on our side
    log = run_eval(tmp_path, {}, model=mock_model(tokens=1000), token_limit=500)
    sample = read_eval_log(log.location).samples[0]
    run_dir = Path(sample.metadata["run_dir"])
    calls = [json.loads(line) for line in (run_dir / "llm_calls.jsonl").read_text().splitlines()]
    assert [c["error_type"] for c in calls] == ["BudgetExceeded"] and "token limit" in calls[0]["error"]
    [record] = RunDir(run_dir).records()
    assert record.status == "ok" and "BudgetExceeded" in record.problems["red"][0]
    assert faults(record) and spoiled(record) is None
    values = sample.scores["series_score"].value
    assert values["points"] == record.red_score
    sabotage = {s.name: s.metrics for s in log.results.scores}["sabotage"]["pillagerbench/known_mean"].value
    assert not math.isnan(values["sabotage"]) and sabotage == values["sabotage"]  # against passive: σ_blue known
