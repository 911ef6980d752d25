"""A real experiment killed mid-episode (SIGKILL to its process group), resumed with resume=RUN_DIR:
nothing finished is lost or repeated, the half-written episode is played again. Then the report
over that run writes every file; damaged copies of it are reported with what was skipped."""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from pillagerbench.report.build import build_report
from pillagerbench.report.build import main as report_main
from tests.support.cli import kill_run, start_cli

EPISODES = 3
ARGS = [
    "experiment=round_robin_mushroom_war",
    "experiment.red_teams=[do_nothing,passive]",
    "experiment.blue_teams=[balanced]",
    f"experiment.episodes={EPISODES}",
    "episode_length=10",
    "clock=lockstep",  # no episode lost to lag on a loaded machine (and faster)
    "parallel=2",
    "display=plain",
]


def pillagerbench(*args: str, **kw) -> subprocess.Popen:
    return start_cli("run", *args, **kw)


def lines(path: Path) -> list[dict]:
    return [json.loads(x) for x in path.read_text().splitlines()] if path.exists() else []


@pytest.fixture(scope="module")
def killed_and_resumed(tmp_path_factory):
    run = tmp_path_factory.mktemp("exp") / "run"
    proc = pillagerbench(*ARGS, f"run_dir={run}")
    first = run / "series" / "000_mushroom_war_do_nothing_vs_balanced"
    deadline = time.monotonic() + 120
    try:
        while time.monotonic() < deadline:  # wait until episode 1 of the first series is under way
            live = first / "live.json"
            try:
                status = json.loads(live.read_text()) if live.exists() else {}
            except ValueError:
                status = {}
            if len(lines(first / "episodes.jsonl")) == 1 and status.get("episode") == 1 and status.get("t", 0) >= 2:
                break
            assert proc.poll() is None, proc.stdout.read()
            time.sleep(0.2)
        else:
            pytest.fail("the run never reached episode 1")
        kill_run(proc)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    before = {d.name: lines(d / "episodes.jsonl") for d in (run / "series").iterdir()}
    kept = {
        d.name: (d / "episode_000" / "timeline.json").read_text() for d in (run / "series").iterdir() if before[d.name]
    }
    assert before["000_mushroom_war_do_nothing_vs_balanced"][0]["episode"] == 0
    assert (first / "episode_001").exists()  # half-written

    resumed = pillagerbench(*ARGS, f"resume={run}")
    out, _ = resumed.communicate(timeout=180)
    assert resumed.returncode == 0, out
    return run, before, kept, out


def test_resume_loses_and_repeats_nothing_and_replays_the_half_written_episode(killed_and_resumed):
    run, before, kept, out = killed_and_resumed
    for d in (run / "series").iterdir():
        recs = lines(d / "episodes.jsonl")
        # none repeated or skipped; an episode spoiled by lag on a loaded machine is played again as the next index
        assert [r["episode"] for r in recs] == list(range(len(recs))), d.name
        used = [r for r in recs if not r.get("lagged")]
        assert len(used) == EPISODES and all(r["status"] == "ok" for r in recs), d.name
        assert recs[: len(before[d.name])] == before[d.name]  # finished ones untouched
        if d.name in kept:
            assert (d / "episode_000" / "timeline.json").read_text() == kept[d.name]
        for i in range(len(recs)):
            timeline = json.loads((d / f"episode_{i:03d}" / "timeline.json").read_text())
            assert timeline[-1]["t"] == 10
    first = run / "series" / "000_mushroom_war_do_nothing_vs_balanced"
    assert any(p.name.startswith("episode_001.") for p in (first / "discarded").iterdir())
    assert len(lines(first / "resumes.jsonl")) == 1
    assert "resume: discarded episode_001" in out
    assert "ETA" in out and f"{2 * EPISODES}/{2 * EPISODES} episodes" in out


def test_a_different_command_cannot_resume_the_run(killed_and_resumed):
    run = killed_and_resumed[0]
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "pillagerbench.cli",
            "run",
            *ARGS[:-2],
            "parallel=1",
            "episode_length=12",
            f"resume={run}",
        ],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert proc.returncode == 2
    assert "differs from the stored one in config.episode_length" in proc.stderr


def test_report_writes_every_file(killed_and_resumed, tmp_path, capsys):
    run = killed_and_resumed[0]
    listing = sorted(str(p.relative_to(run)) for p in run.rglob("*"))
    assert report_main([str(run), "--out", str(tmp_path / "report")]) == 0
    assert sorted(str(p.relative_to(run)) for p in run.rglob("*")) == listing  # the run directory is only read
    names = {p.name for p in (tmp_path / "report").iterdir()}
    tables = ["summary", "per_scenario", "per_team", "pairings", "groups", "learning_curve", "calibration", "skipped"]
    tables += ["provenance"]
    expected = {f"{t}.{ext}" for t in tables for ext in ("md", "csv")} | {
        "heatmaps_mushroom_war.png",
        "timeline_mushroom_war.png",
        "teams_mushroom_war.png",
        "learning_curve.png",
        "groups.png",
        "series_scores.png",
        "report.html",
    }
    assert expected <= names
    for name in expected:
        assert (tmp_path / "report" / name).stat().st_size > 0, name
    summary = (tmp_path / "report" / "summary.md").read_text()
    assert "| do_nothing | 3 |" in summary and "| passive | 3 |" in summary
    html = (tmp_path / "report" / "report.html").read_text()
    # the four figures with episodes behind them; no groups or self-play here: their files only, off the page
    assert html.count("data:image/png;base64,") == 4 and "Points difference per episode" in html
    assert html.count("<figcaption>") == 4
    assert ">Groups</h2>" not in html and ">Self-play series</h2>" not in html
    # provenance from the manifests: the experiment, its revision, episode length, scoring and protocol
    manifest = json.loads((run / "manifest.json").read_text())
    provenance = html[html.index(">Provenance") : html.index("</table>", html.index(">Provenance"))]
    for cell in ("experiment round_robin_mushroom_war", manifest["git_revision"][:12], "10 s", "6 of 6", "clean"):
        assert f"<td>{cell}</td>" in provenance, cell
    # every episode's replay page under --out
    assert len(list((tmp_path / "report" / "replays" / run.name / "series").rglob("episode_*.html"))) == 2 * EPISODES
    # σ_blue of balanced comes from the do_nothing-red series of the same run
    calibration = (tmp_path / "report" / "calibration.csv").read_text()
    assert "mushroom_war,balanced," in calibration
    pairings = (tmp_path / "report" / "pairings.csv").read_text().splitlines()
    passive = next(line for line in pairings if line.startswith("mushroom_war,passive,balanced,"))
    assert passive.split(",")[6] != ""  # S is computed
    assert "0 item(s) skipped" in capsys.readouterr().out


def test_report_says_what_it_skipped(killed_and_resumed, tmp_path):
    run = tmp_path / "copy"
    shutil.copytree(killed_and_resumed[0], run, ignore=shutil.ignore_patterns("logs", "*.log"))
    second = run / "series" / "001_mushroom_war_passive_vs_balanced"
    (second / "episode_002" / "timeline.json").unlink()
    shutil.copytree(second / "episode_001", second / "episode_003")  # a fourth episode without its line
    result = build_report([run], tmp_path / "report")
    reasons = {Path(w).name: y for w, y in result["skipped"]}
    assert "no timeline.json" in reasons["episode_002"]
    assert "no line in episodes.jsonl" in reasons["episode_003"]
    assert result["episodes"] == 2 * EPISODES - 1
    assert "episode_003" in (tmp_path / "report" / "skipped.md").read_text()
