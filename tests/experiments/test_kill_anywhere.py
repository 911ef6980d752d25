"""Killed anywhere, nothing lost or doubled (issue 55, item 6): a run in a subprocess (an experiment on
either clock, a `compare`, a league round, a remote team's experiment on the lockstep clock, on the local
launcher or on Ray), one of its processes SIGKILLed at a seeded moment (the runner, the arena server, a bot,
the remote team's server: tests/support/kill_anywhere.py draws which and when from the seed), the run
handling a child's death itself or resumed after the runner's; then every planned episode exists exactly
once, every JSON and JSONL record parses, the run exported as a bundle passes `verify` and its report counts
what an unkilled run plans, and no process of ours outlives a killed runner. A few seeds here;
`python benchmarks/kill_anywhere.py --seeds 20` draws many. The checker itself is shown failing on
hand-made runs: an episode doubled, lost, half written, a bundle that verify fails or that counts otherwise."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from tests.metrics.fake_runs import write_run
from tests.support.kill_anywhere import bundle_problems, draw, run_kill, series_problems, whole_records
from tests.support.kill_targets import TARGETS

# (target, seed): seeds chosen so that the few cases here kill each kind of process once; the compare, the
# runner on Ray (seed 14: its workers die with it, nothing doubled after the resume) and every other draw are
# the benchmark's (each case costs 20 to 60 s on the 2-core machine, a Ray runner's kill and resume twice that)
CASES = [
    ("league_lockstep", 3),  # the runner, once 1 episode is recorded
    ("experiment_real", 5),  # a bot, 10.6 s after the start (5 s episodes on the real clock)
    ("remote_lockstep", 9),  # the remote team's server, once 2 episodes are recorded; back 1 s later
    ("remote_ray_lockstep", 3),  # the arena server of a remote team's series on Ray, once 1 episode is recorded
]


@pytest.mark.timeout(400)
@pytest.mark.parametrize(("target", "seed"), CASES, ids=[f"{t}-seed{s}" for t, s in CASES])
def test_a_run_killed_anywhere_loses_and_doubles_nothing(tmp_path, target, seed):
    kill = run_kill(tmp_path, TARGETS[target], draw(seed, TARGETS[target]))
    said = f"{kill.summary()}\n{kill.output[-3000:]}"
    assert kill.problems == [], said
    assert not kill.hung, said  # a child's death is the run's to handle: it ends by itself
    assert kill.orphans == [], said  # a killed runner leaves no server or bot behind
    if kill.resumed:
        assert kill.resume_exit == 0, said
    if "lockstep" in target:  # the game clock waits for every bot: no planned episode given up
        assert kill.given_up == 0, said


# --- the checker can fail: a hand-made run (tests/metrics/fake_runs.py) of 3 episodes, each spoiled one way


def _doubled(run: Path) -> None:
    lines = (run / "episodes.jsonl").read_text().splitlines()
    (run / "episodes.jsonl").write_text("\n".join([*lines, lines[-1]]) + "\n")


def _lost(run: Path) -> None:
    lines = (run / "episodes.jsonl").read_text().splitlines()
    (run / "episodes.jsonl").write_text("\n".join(lines[:-1]) + "\n")
    shutil.rmtree(run / "episode_002")


def _torn(run: Path) -> None:
    record = run / "episode_001" / "episode.json"
    record.write_text(record.read_text()[:40])


def _edited(run: Path) -> None:  # a score no timeline shows: the bundle's verify disagrees
    lines = [json.loads(x) for x in (run / "episodes.jsonl").read_text().splitlines()]
    lines[0]["red_score"] += 7
    (run / "episodes.jsonl").write_text("".join(json.dumps(x) + "\n" for x in lines))


SPOILED = {
    "an episode doubled": (_doubled, "episode lines [0, 1, 2, 2], not 0..3 once each"),
    "an episode lost": (_lost, "2 used + 0 given up of 3 planned, 2 played"),
    "a record half written": (_torn, "episode_001/episode.json:1 is not whole JSON"),
}


def _hand_made(tmp_path: Path) -> Path:
    return write_run(tmp_path / "run", "mushroom_war", "passive", "balanced", [(2, 0), (1, 1), (0, 3)])


@pytest.mark.parametrize("how", SPOILED)
def test_the_checker_names_an_episode_lost_doubled_or_half_written(tmp_path, how):
    run = _hand_made(tmp_path)
    assert series_problems(run, 3)[0] == [] and whole_records(tmp_path) == []
    spoil, named = SPOILED[how]
    spoil(run)
    found = series_problems(run, 3)[0] + whole_records(tmp_path)
    assert any(named in p for p in found), found


def test_the_checker_names_a_bundle_that_verify_fails_or_that_counts_otherwise(tmp_path):
    run = _hand_made(tmp_path)  # (the kills above show a bundle that verifies and counts the run passing)
    assert bundle_problems([run], 4, tmp_path / "b") == [
        "the bundle says 3 episode(s) used and its report counts 3; the run used 4"
    ]
    _edited(run)
    assert bundle_problems([run], 3, tmp_path / "c")[0].startswith("verify fails the bundle of the run (killed.tar.gz)")
