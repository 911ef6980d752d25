"""Killed anywhere, nothing lost or doubled (issue 55, item 6), with many seeds: each seed draws a run
(an experiment on the lockstep or the real clock, a `compare`, a league round, a remote team's experiment on
the lockstep clock on the local launcher or on Ray; tests/support/kill_targets.py), a process to SIGKILL
(the runner, the arena server, a bot, a remote team's server) and a moment (a time within the run's span,
or a count of recorded episodes); the run is killed there, resumed when it did not end well by itself,
and checked (tests/support/kill_anywhere.py): every planned episode once, every record whole, the run's
bundle verified, its report counting what an unkilled run counts. Prints one JSON summary: kills by
process kind and moment, resumes that worked, runs with an episode lost or doubled, and every seed's outcome.

    python benchmarks/kill_anywhere.py --seeds 20                 # seeds 0..19, every target
    python benchmarks/kill_anywhere.py --seeds 5 --first 100 --targets experiment_lockstep league_lockstep
    python benchmarks/kill_anywhere.py --reference                # each target unkilled once: its wall time
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from tests.support.kill_anywhere import Kill, draw, run_kill
from tests.support.kill_targets import TARGETS


def one(seed: int, names: list[str], work: Path, reference: bool = False) -> Kill:
    """Seed `seed`'s kill on a target drawn from `names` (the seed chooses it too); with `reference`
    nothing is killed."""
    target = TARGETS[names[seed % len(names)]]
    kill = draw(seed, target)
    if reference:
        kill.asked, kill.at_s, kill.after_records = "none", 10_000.0, None
    return run_kill(work / f"seed_{seed}_{target.name}", target, kill)


def summary(kills: list[Kill]) -> dict:
    """The figures: kills by kind and moment, resumes, problems."""
    by = Counter(f"{k.killed} / {k.moment}" for k in kills)
    return {
        "kills": len(kills),
        "by_target": dict(Counter(k.target for k in kills)),
        "by_kind": dict(Counter(k.killed for k in kills)),
        "by_kind_and_moment": dict(sorted(by.items())),
        "resumed": sum(k.resumed for k in kills),
        "resumes_ok": sum(k.resumed and k.resume_exit == 0 for k in kills),
        "child_kills_the_run_survived": sum(k.killed in ("server", "bot") and k.run_exit == 0 for k in kills),
        "hung_after_a_child_kill": sum(k.hung for k in kills),
        "runner_kills_with_orphans": sum(bool(k.orphans) for k in kills),
        "orphans_by_kind": dict(Counter(kind for k in kills for kind in k.orphans)),
        "lingering_by_kind": dict(Counter(kind for k in kills for kind in k.lingering)),
        "with_problems": sum(bool(k.problems) for k in kills),
        "lost_or_doubled": [k.seed for k in kills if any("not 0.." in p or "given up of" in p for p in k.problems)],
        "half_written": [k.seed for k in kills if any("not whole" in p for p in k.problems)],
        "bundle": [k.seed for k in kills if any("bundle" in p for p in k.problems)],
        "seeds": [k.summary() for k in kills],
    }


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--seeds", type=int, default=20, help="how many seeds")
    p.add_argument("--first", type=int, default=0, help="the first seed")
    p.add_argument("--targets", nargs="+", default=sorted(TARGETS), choices=sorted(TARGETS))
    p.add_argument("--reference", action="store_true", help="kill nothing: each target's unkilled run")
    p.add_argument("--keep", type=Path, help="keep the run directories here (default: a temporary directory)")
    a = p.parse_args(argv)
    kills = []
    with tempfile.TemporaryDirectory() as tmp:
        work = a.keep or Path(tmp)
        seeds = range(len(a.targets)) if a.reference else range(a.first, a.first + a.seeds)
        for seed in seeds:
            kill = one(seed, a.targets, work, a.reference)
            print(json.dumps(kill.summary()), file=sys.stderr, flush=True)
            kills.append(kill)
    print(json.dumps(summary(kills), indent=1))
    return 1 if any(k.problems for k in kills) else 0


if __name__ == "__main__":
    sys.exit(main())
