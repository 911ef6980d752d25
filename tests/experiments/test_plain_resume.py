"""A plain `pillagerbench run` (no experiment=) killed with SIGKILL at three moments, then finished with
resume=RUN_DIR: every episode recorded exactly once and finished, nothing finished rewritten. The kill
comes where the red team (tests/experiments/held_team.py, passive held on a file this test controls)
says it stands: in the pre-game after a record was written, mid-episode, and half way through saving
its state after an episode."""

from __future__ import annotations

import json
import os
import signal
import time
from pathlib import Path

import psutil
import pytest

from tests.support.cli import run_cli, start_cli

ROOT = Path(__file__).resolve().parents[2]
EPISODES = 3
HELD = 1  # the episode the kill comes in (episode 0 is finished then)


def records(run: Path) -> list[dict]:
    path = run / "episodes.jsonl"
    return [json.loads(x) for x in path.read_text().splitlines()] if path.exists() else []


def command(run: Path, hold: Path, at: str) -> list[str]:
    return [
        "scenario=mushroom_war",
        "red=tests.experiments.held_team:HeldPassive",
        f"red.hold={hold}",
        f"red.hold_at={at}",
        f"red.hold_episode={HELD}",
        "blue=do_nothing",
        f"episodes={EPISODES}",
        "episode_length=5",
        "display=plain",
        f"run_dir={run}",
    ]


def kill_when_held(run: Path, hold: Path, at: str) -> list[dict]:
    """Start the run, SIGKILL its process group once the team holds; the records then."""
    hold.write_text("")
    proc = start_cli("run", *command(run, hold, at), cwd=ROOT)
    reached = hold.with_name(hold.name + ".reached")
    deadline = time.monotonic() + 150
    try:
        while not reached.exists():
            assert proc.poll() is None, proc.stdout.read()
            assert time.monotonic() < deadline, f"the run never held at {at}"
            time.sleep(0.05)
        children = psutil.Process(proc.pid).children(recursive=True)
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    _, alive = psutil.wait_procs(children, timeout=15)
    assert not alive, f"processes outlived the killed run: {[p.pid for p in alive]}"
    hold.unlink()
    return records(run)


@pytest.mark.parametrize("at", ["pre_game", "play", "save"])
def test_a_killed_plain_run_resumes_with_nothing_lost_and_nothing_repeated(tmp_path, at):
    run, hold = tmp_path / "run", tmp_path / "hold"
    before = kill_when_held(run, hold, at)
    assert [r["episode"] for r in before] == list(range(HELD))  # killed before episode HELD was recorded
    if at == "save":  # half of red's state after episode HELD on disk, blue's not yet
        assert (run / "state" / f"episode_{HELD:03d}" / "red" / "team.json").exists()
    kept = (run / "episode_000" / "timeline.json").read_text()

    res = run_cli(ROOT, "run", *command(run, hold, at), f"resume={run}", timeout=240)
    assert res.returncode == 0, res.stdout + res.stderr
    after = records(run)
    assert [r["episode"] for r in after] == list(range(EPISODES))
    assert all(r["status"] == "ok" for r in after), [r.get("error") for r in after]
    assert after[: len(before)] == before  # the finished ones untouched
    assert (run / "episode_000" / "timeline.json").read_text() == kept
    for i in range(EPISODES):
        assert json.loads((run / f"episode_{i:03d}" / "timeline.json").read_text())[-1]["t"] == 5
    assert f"resume after {HELD} finished episode(s)" in res.stdout
    assert f"{EPISODES} episode(s), 0 failed" in res.stdout  # the plain run's summary, over the whole run
    assert len((run / "resumes.jsonl").read_text().splitlines()) == 1
