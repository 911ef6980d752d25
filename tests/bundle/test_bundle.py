"""Results bundles: a bundle round-trips (report, symmetry and fidelity from the bundle give the same
tables as from the run directories: a hand-made run with a lagged, a failed and a provider-less episode,
and the real old run of tests/experiments/fixtures); `verify` passes an untouched bundle and names a
tampered score (checksums forged to match), a tampered file, a missing one and an extra one; bad input
is one line and exit 2; the harness failures are in bundle.json apart from the teams' own."""

from __future__ import annotations

import json
import shutil
import tarfile
from pathlib import Path

import pytest

from pillagerbench.cli import commands as cli
from pillagerbench.rundir import RunDir
from pillagerbench.rundir.bundle import CHECKSUMS, INFO, sha256_of
from tests.metrics.fake_runs import write_run

OLD_RUN = Path(__file__).resolve().parents[1] / "experiments" / "fixtures" / "run_6198d49"
SUITE = "suite 1.0@aaaaaaaaaaaaaaaa"
PROVIDER = "llm failed on all 3 call(s); last: APIConnectionError: Connection refused"


@pytest.fixture
def run(tmp_path: Path) -> Path:
    return write_run(
        tmp_path / "run",
        "mushroom_war",
        "passive",
        "balanced",
        [(20, 10), (15, 12), (0, 0), (18, 9)],
        suite=SUITE,
        lagged={1: "server at 12.5 TPS"},
        failed={2: "ArenaServerError: the server died"},
        problems={3: {"red": [PROVIDER], "blue": ["blue's code: ReferenceError: x is not defined"]}},
    )


def export(tmp_path: Path, *runs: Path, replays: bool = False) -> Path:
    out = tmp_path / "bundle.tar.gz"
    assert cli.main(["export", *map(str, runs), "--out", str(out), *["--replays"] * replays]) == 0
    return out


def tables(out: Path) -> dict[str, str]:
    return {p.name: p.read_text() for p in sorted(out.glob("*.csv"))}


def test_a_bundle_reports_the_same_tables_as_its_run_directory(run, tmp_path, capsys):
    bundle = export(tmp_path, run)
    assert cli.main(["report", str(run), "--out", str(tmp_path / "from_dir"), "--no-replays"]) == 0
    assert cli.main(["report", str(bundle), "--out", str(tmp_path / "from_bundle"), "--no-replays"]) == 0
    from_dir, from_bundle = tables(tmp_path / "from_dir"), tables(tmp_path / "from_bundle")
    assert len(from_dir) > 10 and from_dir == from_bundle
    assert "tmp" not in from_bundle["skipped.csv"].replace(str(tmp_path), "")  # named as exported, not unpacked
    for command in ("symmetry", "fidelity"):
        capsys.readouterr()
        assert cli.main([command, str(run)]) == 0
        direct = capsys.readouterr().out
        assert cli.main([command, str(bundle)]) == 0
        assert capsys.readouterr().out == direct


def test_the_old_real_run_round_trips_with_its_replays(tmp_path):
    old = shutil.copytree(OLD_RUN, tmp_path / "old")
    bundle = export(tmp_path, old, replays=True)
    with tarfile.open(bundle) as tar:
        assert any(n.endswith("replay.jsonl.gz") for n in tar.getnames())
        assert not any("/state/" in n for n in tar.getnames())  # the teams' state stays home
    assert cli.main(["report", str(old), "--out", str(tmp_path / "a")]) == 0
    assert cli.main(["report", str(bundle), "--out", str(tmp_path / "b")]) == 0
    assert tables(tmp_path / "a") == tables(tmp_path / "b")
    assert sorted(p.name for p in (tmp_path / "b").rglob("*.html")) == sorted(
        p.name for p in (tmp_path / "a").rglob("*.html")
    )  # the replay pages too
    assert cli.main(["verify", str(bundle)]) == 0


def test_harness_failures_are_counted_apart_from_the_teams_own(run, tmp_path, capsys):
    bundle = export(tmp_path, run)
    with tarfile.open(bundle) as tar:
        info = json.loads(tar.extractfile(INFO).read())  # type: ignore[union-attr]
    faults = info["faults"]
    assert faults["harness_episodes"] == 3 and faults["team_episodes"] == 1
    assert faults["harness_by_kind"] == {"lagged": 1, "failed: the server": 1, "provider unreachable": 1}
    assert cli.main(["report", str(bundle), "--out", str(tmp_path / "r"), "--no-replays"]) == 0
    out = capsys.readouterr().out
    assert "failures: ours (the harness) in 3 episode(s)" in out and "the teams' own" in out
    table = (tmp_path / "r" / "faults.csv").read_text().splitlines()
    assert [line.split(",")[0] for line in table[1:]] == ["harness"] * 3 + ["team"]


@pytest.mark.parametrize(
    "error, whose, kind",
    [
        ("PlayerError: Ryn's bot process exited", "harness", "failed: a bot"),
        ("BudgetExceeded: 4/4 calls", "team", "the team's budget spent"),
        ("ValueError: a team's pre-game raised", "harness", "failed (cause not named)"),
    ],
)
def test_a_failed_episode_is_put_on_whoever_its_error_names(error, whose, kind):
    from pillagerbench.metrics.faults import faults
    from pillagerbench.rundir import EpisodeRecord, Fault

    assert faults(EpisodeRecord.from_dict({"episode": 0, "status": "failed", "error": error})) == [
        Fault(whose, kind, "", error)
    ]


def repack(bundle: Path, tmp_path: Path, change, forge: bool) -> Path:
    """The bundle unpacked, changed by `change(root)`, packed again; with `forge` the checksums are
    recomputed to match (as someone hiding a change would)."""
    root = tmp_path / "unpacked"
    with tarfile.open(bundle) as tar:
        tar.extractall(root, filter="data")
    change(root)
    if forge:
        files = sorted(p for p in (root / "runs").rglob("*") if p.is_file())
        lines = [f"{sha256_of(p.read_bytes())}  {p.relative_to(root).as_posix()}" for p in files]
        (root / CHECKSUMS).write_text("\n".join(lines) + "\n")
    out = tmp_path / "tampered.tar.gz"
    with tarfile.open(out, "w:gz") as tar:
        for p in sorted(root.rglob("*")):
            if p.is_file():
                tar.add(p, p.relative_to(root).as_posix())
    return out


def series_of(root: Path) -> RunDir:
    return RunDir(next((root / "runs").glob("*/*")))


def raise_a_score(root: Path) -> None:
    run = series_of(root)
    lines = run.episodes_path.read_text().splitlines()
    rec = json.loads(lines[0])
    rec["red_score"] = 25
    lines[0] = json.dumps(rec)
    run.episodes_path.write_text("\n".join(lines) + "\n")


def test_verify_passes_an_untouched_bundle(run, tmp_path, capsys):
    assert cli.main(["verify", str(export(tmp_path, run))]) == 0
    out = capsys.readouterr().out
    assert out.splitlines()[-1].endswith(": verified")
    assert f"\n{SUITE}: not a released version" in "\n" + out


def test_verify_names_a_tampered_score_even_with_forged_checksums(run, tmp_path, capsys):
    tampered = repack(export(tmp_path, run), tmp_path, raise_a_score, forge=True)
    assert cli.main(["verify", str(tampered)]) == 1
    found = [line for line in capsys.readouterr().out.splitlines() if line.startswith("disagrees: ")]
    assert any("run/episode_000: clean red score 25 in the record, the timeline ends at 20" in f for f in found)
    assert any("run/episode_000: episode.json differs from its line" in f and "red_score" in f for f in found)


def test_verify_names_a_half_written_episode_record(run, tmp_path, capsys):
    """A record cut short before export (its checksum then matches) is named, not passed."""
    record = RunDir(run).record_path(0)
    record.write_text(record.read_text()[:40])
    assert cli.main(["verify", str(export(tmp_path, run))]) == 1
    found = [line for line in capsys.readouterr().out.splitlines() if line.startswith("disagrees: ")]
    assert any("run/episode_000: episode.json: unreadable (half written?)" in f for f in found), found


def test_verify_names_a_tampered_missing_and_extra_file(run, tmp_path, capsys):
    def damage(root: Path) -> None:
        run = series_of(root)
        timeline = run.timeline_path(3)
        timeline.write_text(timeline.read_text().replace("18", "19"))
        run.record_path(1).unlink()
        (run.path / "notes.txt").write_text("added later")

    tampered = repack(export(tmp_path, run), tmp_path, damage, forge=False)
    assert cli.main(["verify", str(tampered)]) == 1
    out = capsys.readouterr().out
    assert "run/episode_003/timeline.json: content differs from its checksum" in out
    assert "run/episode_001/episode.json: listed in checksums.sha256 but missing" in out
    assert "run/notes.txt: not in checksums.sha256" in out
    assert "run/episode_003: clean red score 18 in the record, the timeline ends at 19" in out


@pytest.mark.parametrize(
    "args, says",
    [
        (["verify", "{tmp}/nothing.tar.gz"], "nothing.tar.gz: no such bundle or run directory"),
        (["verify", "{tmp}/corrupt.tar.gz"], "corrupt.tar.gz: not a readable results bundle"),
        (["report", "{tmp}/corrupt.tar.gz"], "corrupt.tar.gz: not a readable results bundle"),
        (["export", "{tmp}/nothing", "--out", "{tmp}/b.tar.gz"], "nothing: not a run directory or bundle"),
        (["export", "{tmp}", "--out"], "argument --out: expected one argument"),
        (["verify", "{tmp}/corrupt.tar.gz", "--fast"], "unrecognized arguments: --fast"),
        (["symmetry", "{tmp}", "--mix"], "unrecognized arguments: --mix"),
        (["verify", "{tmp}/unsummed.tar.gz"], "unsummed.tar.gz: not a results bundle (no checksums.sha256)"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(tmp_path, capsys, args, says):
    (tmp_path / "corrupt.tar.gz").write_bytes(b"\x1f\x8b not really gzip")
    with tarfile.open(tmp_path / "unsummed.tar.gz", "w:gz") as tar:  # a bundle.json, no checksums
        (tmp_path / INFO).write_text(json.dumps({"format": 1, "runs": []}))
        tar.add(tmp_path / INFO, INFO)
    assert cli.main([a.format(tmp=tmp_path) for a in args]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"pillagerbench {args[0]}: ") and says in err, err


def test_a_league_reads_a_round_handed_over_as_a_bundle(tmp_path, capsys):
    from pillagerbench.league.compose import entrant_of_entry
    from pillagerbench.league.rounds import MATCHES, STAMP
    from pillagerbench.league.spec import League, RosterEntry, save_league

    league = League(entrants=[RosterEntry(t, t) for t in ("do_nothing", "passive", "balanced")])
    save_league(tmp_path / "league", league)
    played = write_run(tmp_path / "round_elsewhere", "mushroom_war", "passive", "balanced", [(20, 10)] * 3)
    stamp = {"entrants": {e.name: entrant_of_entry(e).id for e in league.entrants[1:]}, "game": []}
    (played / STAMP).write_text(json.dumps(stamp))
    bundle = tmp_path / "league" / MATCHES / "elsewhere.tar.gz"
    assert cli.main(["export", str(played), "--out", str(bundle)]) == 0
    assert cli.main(["league", str(tmp_path / "league"), "board"]) == 0
    board = (tmp_path / "league" / "leaderboard.md").read_text()
    assert "3 episodes in 1 rounds" in board
    (played / STAMP).write_text(json.dumps({**stamp, "entrants": {"passive": "another team"}}))
    bundle.unlink()
    assert cli.main(["export", str(played), "--out", str(bundle)]) == 0
    capsys.readouterr()
    assert cli.main(["league", str(tmp_path / "league"), "board"]) == 2
    assert "entrant 'passive' was another team" in capsys.readouterr().err


def test_report_and_calibrate_write_beside_a_bundle_by_default(tmp_path):
    calm = write_run(tmp_path / "calm", "mushroom_war", "do_nothing", "passive", [(0, 20), (0, 24)], suite=SUITE)
    bundle = export(tmp_path, calm)
    assert cli.main(["report", str(bundle), "--no-replays"]) == 0
    assert (tmp_path / "bundle_report" / "report.html").exists()
    assert cli.main(["calibrate", str(bundle)]) == 0
    cal = json.loads((tmp_path / "bundle_calibration.json").read_text())
    assert cal["suites"] == [SUITE] and cal["sources"] == [str(calm)]
