"""Killed anywhere, nothing lost or doubled (issue 55, item 6): a run in a subprocess (an experiment on
either clock, a `compare`, a league round), one of its processes SIGKILLed at a seeded moment (the runner,
the arena server, a bot: tests/support/kill_anywhere.py draws which and when from the seed), the run
handling a child's death itself or resumed after the runner's; then every planned episode exists exactly
once, every JSON and JSONL record parses, the report counts what an unkilled run plans, and no process
outlives a killed runner. A few seeds here; `python benchmarks/kill_anywhere.py --seeds 20` draws many."""

from __future__ import annotations

import pytest

from tests.support.kill_anywhere import draw, run_kill
from tests.support.kill_targets import TARGETS

# (target, seed): seeds chosen so that the few cases here kill each kind of process once; the compare and
# every other draw are the benchmark's (each case costs 30 to 70 s on the 2-core machine)
CASES = [
    ("experiment_lockstep", 0),  # the server, once 3 episodes are recorded
    ("league_lockstep", 3),  # the runner, once 1 episode is recorded
    ("experiment_real", 5),  # a bot, 10.6 s after the start (5 s episodes on the real clock)
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
