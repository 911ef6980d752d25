"""The run directory has one owner (pillagerbench.rundir): no other module spells its file names,
and a run directory written before it (tests/experiments/fixtures/run_6198d49: an experiment
written at 6198d49, two of three episodes finished) still loads, reports and resumes."""

from __future__ import annotations

import ast
import json
import re
import shutil
from pathlib import Path
from typing import get_args

from pillagerbench.config_schema import RunConfig
from pillagerbench.experiments.runner import load_experiment
from pillagerbench.match import SCORINGS
from pillagerbench.metrics.verified import load_runs
from pillagerbench.report.build import main as report_main
from pillagerbench.rundir import EpisodeRecord, RunDir, progress, read_experiment, spoiled
from tests.support.cli import run_cli

SRC = Path(__file__).resolve().parents[2] / "src" / "pillagerbench"
FIXTURE = Path(__file__).parent / "fixtures" / "run_6198d49"
SERIES = "000_mushroom_war_do_nothing_vs_passive"
# a path literal of the run directory (a message may name a file; a path is the name alone or its tail)
NAMES = re.compile(
    r"^/?(episodes\.jsonl|llm_calls\.jsonl|live\.json|experiment\.json|manifest\.json|series\.json|resumes\.jsonl)$"
    r"|^/?episode_($|\d|[{\[*])"
)


def literals(path: Path) -> list[tuple[int, str]]:
    """String constants of a module that are not docstrings or comments' kin (bare string statements)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    bare = {id(n.value) for n in ast.walk(tree) if isinstance(n, ast.Expr) and isinstance(n.value, ast.Constant)}
    return [
        (n.lineno, n.value)
        for n in ast.walk(tree)
        if isinstance(n, ast.Constant) and isinstance(n.value, str) and id(n) not in bare
    ]


def test_only_the_rundir_package_spells_the_run_directorys_names():
    found = [
        f"{path.relative_to(SRC)}:{line}: {text!r}"
        for path in sorted(SRC.rglob("*.py"))
        if "rundir" not in path.parts
        for line, text in literals(path)
        if NAMES.search(text)
    ]
    assert not found, "ask pillagerbench.rundir.RunDir for these paths:\n" + "\n".join(found)


def test_a_record_of_an_earlier_version_reads_with_todays_defaults():
    old = {"scenario": "mushroom_war", "red": "a", "blue": "b", "episode": 3, "red_score": 2.0, "blue_score": 1.0}
    rec = EpisodeRecord.from_dict({**old, "iterations": None, "no_longer_recorded": 1})
    assert (rec.scoring, rec.protocol, rec.iterations) == ("clean", "pillagerbench", {})
    assert rec.scores == {"clean": {"red": 2.0, "blue": 1.0}}


def test_a_run_written_before_the_rundir_package_loads_reports_and_resumes(tmp_path, capsys):
    run = tmp_path / "run"
    shutil.copytree(FIXTURE, run)
    series = RunDir(run / "series" / SERIES)
    before = series.episodes_path.read_text()

    runs = load_runs([run])
    assert sorted(runs.episodes["episode"]) == [0, 1]
    assert set(runs.episodes["scoring"]) == {"clean"} and set(runs.episodes["team_protocol"]) == {"pillagerbench"}
    assert set(runs.episodes["design"]) == {"round_robin"}  # written as "protocol" then
    assert report_main([str(run), "--out", str(tmp_path / "report"), "--no-replays"]) == 0
    assert "2 episode" in capsys.readouterr().out

    res = run_cli(tmp_path, "run", f"resume={run}", "display=plain", timeout=180)
    assert res.returncode == 0, res.stdout + res.stderr
    assert "resume after 2 finished episode(s)" in res.stdout
    assert series.episodes_path.read_text().startswith(before)  # the finished ones untouched
    records = [json.loads(line) for line in series.episodes_path.read_text().splitlines()]
    assert [(r["episode"], r["status"]) for r in records] == [(i, "ok") for i in range(len(records))]
    played = [r["episode"] for r in records[2:] if not spoiled(r)]  # one lagged under load is played again
    assert len(played) == 1 and progress({r["episode"]: r for r in records}, 3).complete
    assert json.loads((series.episode(played[0]) / "timeline.json").read_text())[-1]["t"] == 5


def test_the_design_of_an_experiment_written_when_it_was_called_protocol_reads_back(tmp_path):
    """Before `design`, experiment.json called the experiment's design `protocol` (the word now means
    the LLM teams' loop only); rundir.read_experiment reads it, for every reader."""
    run = tmp_path / "run"
    shutil.copytree(FIXTURE, run)
    assert '"protocol": "round_robin"' in (run / "experiment.json").read_text()
    data = read_experiment(run)
    (series,) = data["series"]
    assert data["experiment"]["design"] == series["design"] == "round_robin"
    assert "protocol" not in data["experiment"] and "protocol" not in series
    assert series["config"]["protocol"] == "pillagerbench"  # the series' team loop, as it was
    assert [s.design for s in load_experiment(run)[1]] == ["round_robin"]
    assert [s.design for s in load_runs([run]).series] == ["round_robin"]


def test_the_scorings_are_named_once():
    assert get_args(RunConfig.model_fields["scoring"].annotation) == tuple(SCORINGS)
