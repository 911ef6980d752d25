"""The command lines, as subprocesses: `inspect eval pillagerbench/mushroom_war --model mockllm/model`
plays a real episode whose log has the sample, its scores and its transcript, and whose run directory
`pillagerbench report` reads; `pillagerbench run llm=inspect` asks Inspect's model."""

from __future__ import annotations

import csv
import json
import math
import os
import subprocess
import sys
from pathlib import Path

from inspect_ai.log import list_eval_logs, read_eval_log

from pillagerbench.rundir import RunDir
from tests.inspect_tasks.conftest import OFFLINE, ROOT

BIN = Path(sys.executable).parent


def offline_env() -> dict[str, str]:
    """The environment with the mock model's token count offline (offline/sitecustomize.py)."""
    return {**os.environ, "PYTHONPATH": os.pathsep.join([str(OFFLINE), str(ROOT)])}


def test_inspect_eval_plays_an_episode_and_the_run_directory_reports(tmp_path: Path) -> None:
    command = [str(BIN / "inspect"), "eval", "pillagerbench/mushroom_war", "--model", "mockllm/model"]
    command += ["-T", "episode_length=20", "-T", "clock=lockstep", "--limit", "1", "-T", f"run_dir={tmp_path / 'runs'}"]
    command += ["--log-dir", str(tmp_path / "logs"), "--display", "plain"]
    out = subprocess.run(command, capture_output=True, text=True, cwd=tmp_path, env=offline_env(), timeout=240)
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    [info] = list_eval_logs(str(tmp_path / "logs"))
    log = read_eval_log(info)
    assert log.status == "success"
    [sample] = log.samples
    assert sample.id == "000_mushroom_war_cot_vs_do_nothing_paper"
    values = sample.scores["series_score"].value
    assert set(values) == {"win", "points", "sabotage", "dominance"}
    assert any(e.event == "model" for e in sample.events)  # the prompt and the mock model's answer
    episode = next(e.data for e in sample.events if e.event == "info" and isinstance(e.data, dict))
    assert "cot.json" in episode["code"]["red"] and episode["status"] == "ok"
    run_dir = Path(sample.metadata["run_dir"])
    [record] = RunDir(run_dir).records()
    assert record.red_entrant.label == "cot@mockllm/model"
    assert json.loads((run_dir / "manifest.json").read_text())["config"]["clock"]["mode"] == "lockstep"
    assert run_dir.parent.parent == tmp_path / "runs"  # the Inspect run: one experiment directory
    report = subprocess.run(
        [str(BIN / "pillagerbench"), "report", str(tmp_path / "runs"), "--out", str(tmp_path / "report")],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert report.returncode == 0, report.stderr
    with open(tmp_path / "report" / "pairings.csv") as f:
        row = next(csv.DictReader(f))
    assert math.isclose(float(row["P"]), values["points"]) and math.isclose(float(row["W"]), values["win"])


def test_pillagerbench_run_asks_inspects_model(tmp_path: Path) -> None:
    run_dir = tmp_path / "run"
    command = [str(BIN / "pillagerbench"), "run", "red=cot", "blue=passive", "llm=inspect", "llm.model=mockllm/model"]
    command += ["episode_length=20", "clock=lockstep", f"run_dir={run_dir}", "display=plain"]
    out = subprocess.run(command, capture_output=True, text=True, cwd=tmp_path, env=offline_env(), timeout=240)
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    [record] = RunDir(run_dir).records()
    assert record.status == "ok" and not record.problems
    calls = [json.loads(line) for line in (run_dir / "llm_calls.jsonl").read_text().splitlines()]
    assert calls and all(
        (c["provider"], c["model"], c["error_type"]) == ("inspect", "mockllm/model", None) for c in calls
    )


def test_pillagerbench_run_with_a_model_inspect_lacks_is_one_line(tmp_path: Path) -> None:
    command = [str(BIN / "pillagerbench"), "run", "red=cot", "llm=inspect", "llm.model=nosuch/model"]
    out = subprocess.run(command + [f"run_dir={tmp_path / 'run'}"], capture_output=True, text=True, cwd=tmp_path)
    assert out.returncode == 2 and len(out.stderr.strip().splitlines()) == 1, out.stderr
    assert "Inspect has no model for llm.model=nosuch/model" in out.stderr and "check llm.model" in out.stderr
    assert not (tmp_path / "run").exists()
