"""What a team is given of its last episode (`TeamContext.last_episode`; a remote team is sent the same
as JSON) is the same whether its series ran through or was killed and resumed: the record as written
(with its duration and post-game problems), its timeline and its chat, read from the run directory.

One plain run is killed in the pre-game of episode 1 (tests/experiments/held_team.py) and resumed: its
episode 1 is given what the resumed process rebuilt from the directory, its episode 2 what the match
handed on without a kill. Each must be what the directory says of the episode before."""

from __future__ import annotations

import json
from pathlib import Path

from pillagerbench.rundir import RunDir, last_seen_json
from tests.experiments.held_team import SEEN
from tests.experiments.test_plain_resume import HELD, ROOT, kill_when_held
from tests.experiments.test_run_directory import unnamed
from tests.support.cli import run_cli

TEAM = "tests.experiments.held_team:SeeingPassive"


def command(run: Path, hold: Path) -> list[str]:
    return [
        "scenario=mushroom_war",
        f"red={TEAM}",
        f"red.hold={hold}",
        "red.hold_at=pre_game",
        f"red.hold_episode={HELD}",
        "blue=do_nothing",
        "episodes=3",
        "episode_length=5",
        "display=plain",
        f"run_dir={run}",
    ]


def as_sent(value) -> object:
    return json.loads(json.dumps(value, default=str))


def test_a_resumed_team_is_given_what_it_would_have_been_given_without_the_kill(tmp_path):
    run, hold = tmp_path / "run", tmp_path / "hold"
    kill_when_held(run, hold, "pre_game", command(run, hold))
    res = run_cli(ROOT, "run", *command(run, hold), f"resume={run}", timeout=240)
    assert res.returncode == 0, res.stdout + res.stderr
    assert f"resume after {HELD} finished episode(s)" in res.stdout

    rundir = RunDir(run)
    finished = rundir.finished()
    assert len(finished) >= 3 and all(r.ok for r in finished.values())
    assert json.loads((rundir.episode(0) / "red" / SEEN).read_text()) is None  # nothing before episode 0
    for i in sorted(finished)[1:]:  # episode HELD given after the resume, the later ones without a kill
        given = json.loads((rundir.episode(i) / "red" / SEEN).read_text())
        expected = as_sent(last_seen_json(rundir.last_seen(finished[i - 1])))
        assert given == expected, (
            f"episode {i}: {sorted(k for k in expected['record'] if given['record'].get(k) != expected['record'][k])}"
        )
        assert given["record"]["duration_s"] > 0 and given["record"]["episode"] == i - 1
    assert all(unnamed(rundir.episode(i)) == [] for i in finished)  # a run of today's: every file named by rundir
