"""launcher=ray on a local Ray instance: a series runs as a Ray task and writes the same run directory.
Ray is in the test extra (pyproject.toml), so this runs in every suite, CI's included. On the lockstep
clock (issue 38, item 6): a Ray task plays game time as the local runner does."""

from __future__ import annotations

import json
import subprocess
import sys


def test_an_experiment_runs_on_a_local_ray_instance(tmp_path):
    run = tmp_path / "run"
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "pillagerbench.cli",
            "run",
            "experiment=round_robin_mushroom_war",
            "experiment.red_teams=[passive]",
            "experiment.blue_teams=[do_nothing,balanced]",
            "experiment.episodes=1",
            "episode_length=10",
            "clock=lockstep",
            "launcher=ray",
            "display=plain",
            f"run_dir={run}",
        ],
        capture_output=True,
        text=True,
        timeout=180,
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "(ray)" in proc.stdout
    for name in ("000_mushroom_war_passive_vs_do_nothing", "001_mushroom_war_passive_vs_balanced"):
        recs = [json.loads(x) for x in (run / "series" / name / "episodes.jsonl").read_text().splitlines()]
        assert [(r["episode"], r["status"], r["lagged"]) for r in recs] == [(0, "ok", False)]
        assert (
            json.loads((run / "series" / name / "manifest.json").read_text())["config"]["clock"]["mode"] == "lockstep"
        )
