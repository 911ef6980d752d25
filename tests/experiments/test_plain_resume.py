"""A plain `pillagerbench run` (no experiment=) killed with SIGKILL at four moments, then finished with
resume=RUN_DIR: every episode recorded exactly once and finished, nothing finished rewritten, and the
run reads as three episodes. The kill comes as soon as episodes.jsonl has grown by the record of
episode 0 ("record"), or where the red team (tests/experiments/held_team.py, passive held on a file
this test controls) says it stands: in the next pre-game (its arena reset, nothing of it played),
mid-episode, and half way through saving its state after an episode. The kill after a record plays on
the lockstep clock and resumes on it; a copy of the run killed mid-episode, without the teams' state, is
refused instead of resumed."""

from __future__ import annotations

import json
import os
import shutil
import signal
import time
from pathlib import Path

import pytest

from pillagerbench.cli import commands as cli
from pillagerbench.metrics.verified import load_runs
from pillagerbench.rundir import EpisodeRecord, spoiled
from tests.support.cli import kill_run, run_cli, start_cli

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


def kill_when_held(run: Path, hold: Path, at: str, args: list[str] | None = None) -> list[dict]:
    """Start the run (`args`: its command, default `command`'s), SIGKILL its process group once the team
    holds (or, at "record", once episode 0 is recorded); the records then."""
    hold.write_text("")
    proc = start_cli("run", *(args or command(run, hold, at)), cwd=ROOT)
    reached = hold.with_name(hold.name + ".reached")
    deadline = time.monotonic() + 150
    try:
        while not (reached.exists() or at == "record" and len(records(run)) == HELD):
            assert proc.poll() is None, proc.stdout.read()
            assert time.monotonic() < deadline, f"the run never held at {at}"
            time.sleep(0.01)
        kill_run(proc)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    hold.unlink()
    return records(run)


# The kill right after a record plays on the lockstep clock (issue 38): the resumed run keeps its clock,
# every episode stamped so; the other three moments on the real clock (the default).
ON_LOCKSTEP = "record"


@pytest.mark.parametrize("at", ["record", "pre_game", "play", "save"])
def test_a_killed_plain_run_resumes_with_nothing_lost_and_nothing_repeated(tmp_path, monkeypatch, capsys, at):
    run, hold = tmp_path / "run", tmp_path / "hold"
    args = [*command(run, hold, at), *(["clock=lockstep"] if at == ON_LOCKSTEP else [])]
    before = kill_when_held(run, hold, at, args)
    assert [r["episode"] for r in before] == list(range(HELD))  # killed before episode HELD was recorded
    if at == "save":  # half of red's state after episode HELD on disk, blue's not yet
        assert (run / "state" / f"episode_{HELD:03d}" / "red" / "team.json").exists()
    if at == "play":
        refused_without_the_teams_state(run, monkeypatch, capsys)
    kept = (run / "episode_000" / "timeline.json").read_text()

    res = run_cli(ROOT, "run", *args, f"resume={run}", timeout=240)
    assert res.returncode == 0, res.stdout + res.stderr
    after = records(run)
    assert [r["episode"] for r in after] == list(range(len(after)))  # every index once: none lost, none repeated
    # an episode spoiled on our side (lag on a loaded machine) is kept and played again as the next index
    used = [r["episode"] for r in after if not spoiled(EpisodeRecord.from_dict(r))]
    assert len(used) == EPISODES, [(r["episode"], spoiled(EpisodeRecord.from_dict(r))) for r in after]
    assert all(r["status"] == "ok" for r in after), [r.get("error") for r in after]
    assert after[: len(before)] == before  # the finished ones untouched
    assert (run / "episode_000" / "timeline.json").read_text() == kept
    for i in range(len(after)):
        assert json.loads((run / f"episode_{i:03d}" / "timeline.json").read_text())[-1]["t"] == 5
    assert f"resume after {HELD} finished episode(s)" in res.stdout
    assert f"{len(after)} episode(s), 0 failed" in res.stdout  # the plain run's summary, over the whole run
    assert len((run / "resumes.jsonl").read_text().splitlines()) == 1
    assert sorted(load_runs([run]).episodes["episode"]) == used  # and it reads as one run
    if at == ON_LOCKSTEP:  # every episode, before the kill and after, played on that clock and stamped so
        assert [r["conditions"].get("clock.mode") for r in after] == ["lockstep"] * EPISODES
        assert all(r["lagged"] is False for r in after), after  # it waits for every bot: none played again


def refused_without_the_teams_state(run: Path, monkeypatch, capsys) -> None:
    """A copy of the killed run without `state/`, as a plain run written before plain runs kept state: its
    resume would start the teams from scratch, so it is refused (one line, exit 2; in-process, cli.main),
    not played. The run itself is left to the resume that follows."""
    copy = run.with_name("without_state")
    shutil.copytree(run, copy)
    shutil.rmtree(copy / "state")
    monkeypatch.chdir(ROOT)
    code = cli.main(["run", f"resume={copy}"])
    out, err = capsys.readouterr()
    assert code == 2, out + err
    (line,) = err.strip().splitlines()
    assert line.startswith("pillagerbench run: cannot resume: red's state after episode 0 is missing (")
    assert str(copy / "state") in line, line  # the copy's, not the run's
    assert [r["episode"] for r in records(copy)] == [0]
