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

from pillagerbench.config.schema import RunConfig
from pillagerbench.config.sides import SIDES
from pillagerbench.experiments.runner import load_experiment
from pillagerbench.match import SCORINGS
from pillagerbench.metrics.verified import load_runs
from pillagerbench.report.build import main as report_main
from pillagerbench.rundir import EpisodeRecord, RunDir, progress, read_experiment, spoiled
from pillagerbench.rundir import names as N
from tests.support.cli import run_cli

SRC = Path(__file__).resolve().parents[2] / "src" / "pillagerbench"
FIXTURE = Path(__file__).parent / "fixtures" / "run_6198d49"
# a plain run written at 672b488 (before records were typed), SIGKILLed once two of its three episodes
# were recorded (episode 0 played under lag: spoiled; episode_002 half-written); logs not committed
PLAIN = Path(__file__).parent / "fixtures" / "plain_672b488"
SERIES = "000_mushroom_war_do_nothing_vs_passive"
# every file of a run directory, of an episode's directory and of a team's saved state, by its name in
# rundir/names.py (a message may name a file; a path literal is the name alone or its tail)
FILES = (
    *(
        N.EPISODES,
        N.LEDGER,
        N.LIVE,
        N.EXPERIMENT,
        N.MANIFEST,
        N.SERIES,
        N.RESUMES,
        f"{N.SERVER_LOG}.log",
        N.CALIBRATION,
    ),
    *(N.RECORD, N.timeline_name("clean"), N.timeline_name("upstream"), N.CHAT, N.WORLD_EVENTS, N.GAME_MASTER),
    *(N.REPLAY, N.REPLAY_PAGE, N.TASK_ERROR, N.TEAM_STATE, N.LEDGER_OFFSET),
)
NAMES = re.compile(r"^/?(" + "|".join(map(re.escape, FILES)) + r")$|^/?episode_($|\d|[{\[*])|^/?events/")


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


def unnamed(episode_dir: Path) -> list[str]:
    """The files of an episode's directory that rundir/names.py does not name (a side's directory and a
    player's events file are named by the side and the player)."""
    named = {N.RECORD, N.CHAT, N.WORLD_EVENTS, N.GAME_MASTER, N.REPLAY, N.REPLAY_PAGE}
    out = []
    for path in sorted(p for p in episode_dir.rglob("*") if p.is_file()):
        top, *rest = path.relative_to(episode_dir).parts
        if top in SIDES or top == N.EVENTS and len(rest) == 1 and path.suffix == ".jsonl":
            continue
        if top not in named and not re.fullmatch(r"timeline(_\w+)?\.json", top) and not top.endswith(N.TASK_ERROR):
            out.append(path.relative_to(episode_dir).as_posix())
    return out


def test_every_file_of_an_episode_directory_is_named_by_rundir():
    episodes = [d for _, d in RunDir(FIXTURE / "series" / SERIES).episode_dirs()]
    assert episodes and all(unnamed(d) == [] for d in episodes), [unnamed(d) for d in episodes]


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
    played = [r["episode"] for r in records[2:] if not spoiled(EpisodeRecord.from_dict(r))]  # lagged: played again
    assert len(played) == 1 and progress(series.finished(), 3).complete
    assert json.loads((series.episode(played[0]) / "timeline.json").read_text())[-1]["t"] == 5


def test_the_design_of_an_experiment_written_when_it_was_called_protocol_reads_back(tmp_path):
    """Before `design`, experiment.json called the experiment's design `protocol` (the word now means
    the LLM teams' loop only); rundir.read_experiment reads it, for every reader."""
    run = tmp_path / "run"
    shutil.copytree(FIXTURE, run)
    assert '"protocol": "round_robin"' in (run / "experiment.json").read_text()
    data = read_experiment(run)
    (series,) = data.series
    assert data.experiment["design"] == series["design"] == "round_robin"
    assert "protocol" not in data.experiment and "protocol" not in series
    assert series["config"]["protocol"] == "pillagerbench"  # the series' team loop, as it was
    assert [s.design for s in load_experiment(run)[1]] == ["round_robin"]
    assert [s.design for s in load_runs([run]).series] == ["round_robin"]


def test_the_scorings_are_named_once():
    assert get_args(RunConfig.model_fields["scoring"].annotation) == tuple(SCORINGS)


def test_a_manifest_of_an_earlier_version_reads_and_writes_back_as_it_was(tmp_path):
    for path in sorted([*FIXTURE.rglob(N.MANIFEST), *PLAIN.rglob(N.MANIFEST)]):
        manifest = RunDir(path.parent).manifest()
        assert manifest is not None and manifest.config["seed"] == 0
        RunDir(tmp_path).write_manifest(manifest)
        assert json.loads(RunDir(tmp_path).manifest_path.read_text()) == json.loads(path.read_text())
        assert list(json.loads(RunDir(tmp_path).manifest_path.read_text())) == list(json.loads(path.read_text()))
    series = RunDir(FIXTURE / "series" / SERIES).manifest()
    assert series is not None and series.scenario_version != "?" and series.suite_label == "unversioned"


def test_a_plain_run_written_before_records_were_typed_loads_reports_and_resumes(tmp_path, capsys):
    run = tmp_path / "run"
    shutil.copytree(PLAIN, run)
    rundir = RunDir(run)
    before = rundir.episodes_path.read_text()
    finished = rundir.finished()
    assert sorted(finished) == [0, 1] and spoiled(finished[0]) == "lagged" and not spoiled(finished[1])
    assert finished[1].red_entrant is not None and finished[1].suite != "unversioned"

    runs = load_runs([run])
    assert list(runs.episodes["episode"]) == [1] and list(runs.spoiled["episode"]) == [0]
    assert report_main([str(run), "--out", str(tmp_path / "report"), "--no-replays"]) == 0
    capsys.readouterr()

    res = run_cli(tmp_path, "run", f"resume={run}", "display=plain", timeout=240)
    assert res.returncode == 0, res.stdout + res.stderr
    assert "resume after 2 finished episode(s)" in res.stdout
    assert rundir.episodes_path.read_text().startswith(before)  # the finished ones untouched
    assert progress(rundir.finished(), 3).complete and all(r.ok for r in rundir.records())
    assert any(p.name.startswith("episode_002") for p in (run / "discarded").iterdir())  # the half-written one


def test_every_file_of_the_plain_runs_episodes_is_named_by_rundir():
    episodes = [d for _, d in RunDir(PLAIN).episode_dirs()]
    assert len(episodes) == 3 and all(unnamed(d) == [] for d in episodes), [unnamed(d) for d in episodes]
