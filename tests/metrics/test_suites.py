"""No silent mixing of suite versions: report, fidelity, symmetry, calibrate and the league refuse
episodes of two suite versions in one table (one line naming the versions and the runs, exit 2), and
with --mix-suites (league: mix_suites=true) every table says so; a run from before suite versions
reads as "unversioned", and a run played today names this installation's suite."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from pillagerbench.cli import commands as cli
from pillagerbench.league import results
from pillagerbench.league.board import write_board
from pillagerbench.league.spec import League, RosterEntry
from pillagerbench.metrics.runs import ReportError
from pillagerbench.metrics.verified import load_runs
from pillagerbench.rundir import EpisodeRecord
from pillagerbench.suite.version import UNVERSIONED, current
from tests.metrics.fake_runs import write_run

OLD_RUN = Path(__file__).resolve().parents[1] / "experiments" / "fixtures" / "run_6198d49"
A, B = "suite 1.0@aaaaaaaaaaaaaaaa", "suite 1.1@bbbbbbbbbbbbbbbb"
MARK = f"mixed suite versions or conditions: {A}, {B}"


@pytest.fixture
def two(tmp_path: Path) -> tuple[Path, Path]:
    a = write_run(tmp_path / "a", "mushroom_war", "do_nothing", "passive", [(0, 20), (0, 22)], suite=A)
    b = write_run(tmp_path / "b", "mushroom_war", "passive", "do_nothing", [(21, 0), (19, 0)], suite=B)
    return a, b


COMMANDS = {
    "report": ["--no-replays", "--out", "{out}"],
    "fidelity": [],
    "symmetry": [],
    "calibrate": ["--out", "{out}/calibration.json"],
}


@pytest.mark.parametrize("command", COMMANDS)
def test_two_suite_versions_are_refused_in_one_line(two, tmp_path, capsys, command):
    extra = [e.format(out=tmp_path / "out") for e in COMMANDS[command]]
    assert cli.main([command, *map(str, two), *extra]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(
        f"pillagerbench {command}: refusing to mix suite versions or conditions: "
    )
    assert f"{A} in {two[0]}" in err and f"{B} in {two[1]}" in err and "--mix-suites" in err
    assert not (tmp_path / "out" / "summary.md").exists()


@pytest.mark.parametrize("command", COMMANDS)
def test_mixing_when_asked_is_said(two, tmp_path, capsys, command):
    extra = [e.format(out=tmp_path / "out") for e in COMMANDS[command]]
    (tmp_path / "out").mkdir()
    assert cli.main([command, *map(str, two), *extra, "--mix-suites"]) == 0
    assert MARK in capsys.readouterr().out


def test_every_table_of_a_mixed_report_says_so(two, tmp_path, capsys):
    out = tmp_path / "report"
    assert cli.main(["report", *map(str, two), "--no-replays", "--out", str(out), "--mix-suites"]) == 0
    tables = sorted(out.glob("*.md"))
    assert len(tables) > 10
    for table in tables:
        assert MARK in table.read_text().splitlines()[0], table.name
    assert (out / "report.html").read_text().count(MARK) >= len(tables)
    provenance = (out / "provenance.csv").read_text()
    assert f"{A}" in provenance and f"{B}" in provenance  # each run's own suite


def test_the_league_refuses_mixed_rounds_unless_asked(two, tmp_path, monkeypatch):
    monkeypatch.setattr(results, "round_dirs", lambda league_dir: list(two))
    league = League(entrants=[RosterEntry(t, t) for t in ("do_nothing", "passive")])
    with pytest.raises(ReportError, match="refusing to mix suite versions or conditions"):
        write_board(tmp_path, league)
    league.mix_suites = True
    write_board(tmp_path, league)
    board = (tmp_path / "leaderboard.md").read_text()
    assert f"## Leaderboard [{MARK}" in board and "Head to head, mushroom_war (row's" in board
    assert all(MARK in line for line in board.splitlines() if line.startswith("## "))


def test_an_old_run_reads_as_unversioned_and_a_new_record_names_this_suite(tmp_path):
    shutil.copytree(OLD_RUN, tmp_path / "old")
    runs = load_runs([tmp_path / "old"])
    assert runs.suites == [UNVERSIONED] and set(runs.episodes["suite"]) == {UNVERSIONED}
    new = write_run(tmp_path / "new", "mushroom_war", "do_nothing", "passive", [(0, 20)], length=5, suite=A)
    with pytest.raises(ReportError, match=f"unversioned in {tmp_path / 'old'}"):
        load_runs([tmp_path / "old", new])
    assert EpisodeRecord.from_dict({"scenario": "s", "red": "a", "blue": "b", "episode": 0}).suite == UNVERSIONED
    assert EpisodeRecord("s", "a", "b", 0).suite == current()["label"]


def test_every_manifest_names_the_suite(tmp_path):
    from types import SimpleNamespace

    from pillagerbench.config.compose import load_config
    from pillagerbench.config.schema import RunConfig, RunnerConfig
    from pillagerbench.experiments.runner import write_experiment
    from pillagerbench.rundir import RunDir
    from pillagerbench.rundir.manifest import match_manifest

    scenario = SimpleNamespace(key="mushroom_war", title="Mushroom War", version="1")
    RunDir(tmp_path / "run").write_manifest(match_manifest(RunConfig.of(load_config([])), scenario))
    runner = RunnerConfig.model_validate({"experiment": {"name": "x", "design": "fidelity"}})
    write_experiment(tmp_path / "exp", runner, [], [])
    for run in ("run", "exp"):
        assert RunDir(tmp_path / run).manifest().suite == current()


def test_the_same_files_named_before_and_after_their_hash_was_recorded_are_one_version(tmp_path):
    dev, released = "suite 1.0+dev@cccccccccccccccc", "suite 1.0@cccccccccccccccc"
    write_run(tmp_path / "a", "mushroom_war", "do_nothing", "passive", [(0, 20)], suite=dev)
    write_run(tmp_path / "b", "mushroom_war", "do_nothing", "passive", [(0, 22)], suite=released)
    assert load_runs([tmp_path / "a", tmp_path / "b"]).suites == [f"{dev} = {released}"]


def test_a_version_re_recorded_for_a_change_that_moved_no_score_is_still_one_version(tmp_path):
    from pillagerbench.suite.version import label, same_version

    earlier = next(h for h, now in same_version().items() if h != now)  # suite 1.1 before issue 40's registry
    old, new = label("suite 1.1", earlier), current()["label"]
    a = write_run(tmp_path / "a", "mushroom_war", "do_nothing", "passive", [(0, 20)], length=5, suite=old)
    b = write_run(tmp_path / "b", "mushroom_war", "do_nothing", "passive", [(0, 22)], length=5, suite=new)
    assert load_runs([a, b]).suites == [f"{old} = {new}"]
    c = write_run(tmp_path / "c", "mushroom_war", "do_nothing", "passive", [(0, 21)], length=5, suite=B)
    with pytest.raises(ReportError, match="refusing to mix suite versions"):
        load_runs([a, c])
