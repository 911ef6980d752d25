"""Bundles are checked when read (issue 37 item 6): report, symmetry, fidelity, calibrate, export and the
league verify a bundle first and refuse one whose score was edited (checksums forged to match) in one
line, exit 2, nothing written; --no-verify (league: no_verify=true) reads it anyway and every table's
title and the notes say it was not verified; `verify` names a manifest (a run's, an experiment's) whose
suite version is not its episodes'; a good bundle still reports the numbers of its run directory."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from pillagerbench.cli import commands as cli
from pillagerbench.rundir import RunDir
from tests.bundle.test_bundle import OLD_RUN, SUITE, export, raise_a_score, repack, series_of, tables
from tests.metrics.fake_runs import write_run

MARK = "bundle not verified: "
OTHER = "suite 0.9@0123456789abcdef"


@pytest.fixture
def run(tmp_path: Path) -> Path:
    return write_run(
        tmp_path / "run", "mushroom_war", "do_nothing", "passive", [(0, 20), (0, 22), (0, 18)], suite=SUITE
    )


@pytest.fixture
def edited(run: Path, tmp_path: Path) -> Path:
    """The run's bundle with episode 0's red score raised to 25, its checksums forged to match."""
    return repack(export(tmp_path, run), tmp_path, raise_a_score, forge=True)


READERS = {
    "report": ["--no-replays", "--out", "{tmp}/out"],
    "symmetry": [],
    "fidelity": [],
    "calibrate": ["--out", "{tmp}/out/calibration.json"],
}


def _args(command: str, tmp: Path) -> list[str]:
    return [a.format(tmp=tmp) for a in READERS[command]]


@pytest.mark.parametrize("command", [*READERS, "export"])
def test_a_bundle_with_an_edited_score_is_refused_in_one_line(edited, tmp_path, capsys, command):
    extra = ["--out", str(tmp_path / "out" / "again.tar.gz")] if command == "export" else _args(command, tmp_path)
    capsys.readouterr()
    assert cli.main([command, str(edited), *extra]) == 2
    captured = capsys.readouterr()
    err = captured.err
    assert err.count("\n") == 1 and err.startswith(f"pillagerbench {command}: {edited}: fails its checks ("), err
    assert "clean red score 25 in the record, the timeline ends at 0" in err and "--no-verify" in err
    assert not (tmp_path / "out").exists() and not captured.out  # nothing written, nothing printed


def test_no_verify_reads_it_and_every_table_and_the_notes_say_so(edited, run, tmp_path, capsys):
    out = tmp_path / "report"
    assert cli.main(["report", str(edited), "--no-replays", "--out", str(out), "--no-verify"]) == 0
    printed = capsys.readouterr().out
    mark = f"{MARK}{edited} (--no-verify"
    assert mark in printed  # the notes
    md = sorted(out.glob("*.md"))
    assert len(md) > 10
    for table in md:
        assert mark in table.read_text().splitlines()[0], table.name
    assert (out / "report.html").read_text().count(mark) >= len(md)
    # the edited score is what it read: do_nothing's P moves from the run directory's
    assert cli.main(["report", str(run), "--no-replays", "--out", str(tmp_path / "direct")]) == 0
    assert (out / "summary.csv").read_text() != (tmp_path / "direct" / "summary.csv").read_text()
    (tmp_path / "out").mkdir()
    for command in ("symmetry", "fidelity", "calibrate"):
        capsys.readouterr()
        assert cli.main([command, str(edited), *_args(command, tmp_path), "--no-verify"]) == 0, command
        assert mark in capsys.readouterr().out, command
    calibration = json.loads((tmp_path / "out" / "calibration.json").read_text())
    assert any(mark in n for n in calibration["notes"])


def test_a_good_bundle_reports_its_run_directorys_numbers_and_says_it_was_checked(run, tmp_path, capsys):
    bundle = export(tmp_path, run)
    assert cli.main(["report", str(run), "--no-replays", "--out", str(tmp_path / "direct")]) == 0
    capsys.readouterr()
    assert cli.main(["report", str(bundle), "--no-replays", "--out", str(tmp_path / "checked")]) == 0
    printed = capsys.readouterr().out
    assert f"read from the results bundle {bundle}, its checks passed" in printed and MARK not in printed
    assert tables(tmp_path / "direct") == tables(tmp_path / "checked")


def _manifest_says(suite: str):
    def change(root: Path) -> None:
        path = series_of(root).manifest_path
        manifest = json.loads(path.read_text())
        path.write_text(json.dumps({**manifest, "suite": {"label": suite}}))

    return change


def test_verify_names_a_manifest_whose_suite_is_not_its_episodes(run, tmp_path, capsys):
    mismatched = repack(export(tmp_path, run), tmp_path, _manifest_says(OTHER), forge=True)
    assert cli.main(["verify", str(mismatched)]) == 1
    found = [line for line in capsys.readouterr().out.splitlines() if line.startswith("disagrees: ")]
    assert found == [f"disagrees: runs/00/run/manifest.json: says {OTHER}, but 3 episode(s) say {SUITE} (0, 1, 2)"]
    assert cli.main(["report", str(mismatched), "--no-replays", "--out", str(tmp_path / "out")]) == 2
    assert f"manifest.json: says {OTHER}, but 3 episode(s) say {SUITE}" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_episodes_of_a_resume_under_another_suite_agree_with_the_manifest_that_says_so(run, tmp_path, capsys):
    """A run begun under OTHER and resumed under SUITE: its resumes.jsonl names SUITE, so its episodes agree
    with its manifest (a report of episodes under several suites still refuses to mix them unasked)."""
    manifest = json.loads((run / "manifest.json").read_text())
    (run / "manifest.json").write_text(json.dumps({**manifest, "suite": {"label": OTHER}}))
    RunDir(run).note_resume([0], [], SUITE)
    assert cli.main(["verify", str(export(tmp_path, run))]) == 0, capsys.readouterr().out


def test_the_same_suite_under_its_released_name_is_no_mismatch(run, tmp_path, capsys):
    renamed = SUITE.replace("suite 1.0@", "suite 1.0+dev@")  # one version: same hash, named before its release
    bundle = repack(export(tmp_path, run), tmp_path, _manifest_says(renamed), forge=True)
    assert cli.main(["verify", str(bundle)]) == 0, capsys.readouterr().out


def test_the_league_refuses_a_handed_over_bundle_that_fails_unless_no_verify(tmp_path, capsys):
    from pillagerbench.league.compose import entrant_of_entry
    from pillagerbench.league.rounds import MATCHES, STAMP
    from pillagerbench.league.spec import League, RosterEntry, save_league

    league = League(entrants=[RosterEntry(t, t) for t in ("do_nothing", "passive", "balanced")])
    save_league(tmp_path / "league", league)
    played = write_run(tmp_path / "elsewhere", "mushroom_war", "passive", "balanced", [(20, 10)] * 3, suite=SUITE)
    (played / STAMP).write_text(
        json.dumps({"entrants": {e.name: entrant_of_entry(e).id for e in league.entrants[1:]}, "game": []})
    )
    handed = tmp_path / "league" / MATCHES / "elsewhere.tar.gz"
    handed.parent.mkdir()
    repack(export(tmp_path, played), tmp_path, raise_a_score, forge=True).rename(handed)
    capsys.readouterr()
    for command in ("board", "play"):
        assert cli.main(["league", str(tmp_path / "league"), command]) == 2, command
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and f"{handed}: fails its checks (" in err and "no_verify=true" in err, err
        assert not (tmp_path / "league" / "leaderboard.md").exists()
        assert not list((tmp_path / "league" / MATCHES).glob("round_*"))  # nothing played
    assert cli.main(["league", str(tmp_path / "league"), "board", "no_verify=true"]) == 0
    board = (tmp_path / "league" / "leaderboard.md").read_text()
    assert f"{MARK}{handed}" in board and "3 episodes in 1 rounds" in board
    assert all(MARK in line for line in board.splitlines() if line.startswith("## "))


def test_verify_checks_an_experiments_manifest_and_each_series_manifest(tmp_path, capsys):
    old = shutil.copytree(OLD_RUN, tmp_path / "old")  # a real experiment, from before suite versions

    def change(root: Path) -> None:
        top = next((root / "runs").glob("*/old"))
        path = top / "manifest.json"
        path.write_text(json.dumps({**json.loads(path.read_text()), "suite": {"label": OTHER}}))

    mismatched = repack(export(tmp_path, old), tmp_path, change, forge=True)
    assert cli.main(["verify", str(mismatched)]) == 1
    found = [line for line in capsys.readouterr().out.splitlines() if line.startswith("disagrees: ")]
    assert found == [f"disagrees: runs/00/old/manifest.json: says {OTHER}, but 2 episode(s) say unversioned (0, 1)"]
