"""The runs tests/support/kill_anywhere.py kills, as data: each a `Target` with its command, its resume, its
series directories and what an unkilled run of it uses. Short episodes of built-in teams, so a kill and
its resume take seconds: an experiment of 2 series x 2 episodes (lockstep 10 s, or real-clock 5 s), a
`compare` of passive and balanced against do_nothing under wide bounds, a league's first round
(budget 4 episodes: one match and its side-swapped twin, 2 episodes each), and on the lockstep clock a
remote team (examples/remote_team.py, served over HTTP from a process of its own, which a seed may kill
too: its owner starts it again on its port a moment later) against do_nothing and balanced, 2 episodes
each, on the local launcher or on Ray."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import psutil

from tests.support.kill_anywhere import KINDS, ROOT, Target

EXPERIMENT = [
    "experiment=round_robin_mushroom_war",
    "experiment.red_teams=[passive]",
    "experiment.blue_teams=[do_nothing,balanced]",
    "experiment.episodes=2",
    "parallel=2",
    "display=plain",
]
COMPARE = ["passive", "balanced", "opponent=do_nothing", "sprt.p1=0.9", "sprt.alpha=0.3", "sprt.beta=0.3", "cap=2"]
# mix_suites: the league's board refuses rounds of two suite hashes, which a working tree edited while the run
# was killed and resumed stamps (the checker's report mixes them too)
LEAGUE = ["budget.episodes=4", "episodes_per_match=2", "parallel=2", "display=plain", "mix_suites=true"]
REMOTE = [
    "experiment=main_benchmark",
    "experiment.team=remote",
    "experiment.scenarios=[mushroom_war]",
    "experiment.opponents=[do_nothing,balanced]",
    "experiment.episodes=2",
    "experiment.repetitions=1",
    "outage_wait_s=60",  # a team's server down past its restart is a failure, not a 15 min wait
    "parallel=2",
    "display=plain",
]
# Ray's own agents: after a killed driver took the local instance down with it, they try to tell its
# dead GCS and live on for a while (ray/_private/process_watcher.py); no series runs in them
RAY_AGENTS = ("ray::DashboardAgent", "ray::RuntimeEnvAgent")
TEAM = "team"  # the kind of a remote team's server among the processes a seed may kill
TEAM_FILE = "team.json"  # its pid and address, in the kill's directory


def _run(root: Path) -> Path:
    return root / "run"


def _league(root: Path) -> Path:
    return root / "L"


def _planned(run: Path) -> dict[Path, int]:
    """Each series of an experiment's run directory and its planned episodes (none before it is written)."""
    from pillagerbench.experiments.runner import load_experiment

    if not (run / "experiment.json").exists():
        return {}
    _, specs, dirs = load_experiment(run)
    return {dirs[s.id]: s.episodes for s in specs}


def _again(start: list[str], resume: list[str], marker: str):
    """The resume, or the start again when the kill came before the run directory was written (what a
    user does: `resume=` of a directory that holds no run is refused in one line)."""

    def command(root: Path) -> list[str]:
        return resume if (root / marker).exists() else start

    return command


def experiment(clock: str, length: int, span_s: float) -> Target:
    def start(root: Path) -> list[str]:
        return ["run", *EXPERIMENT, f"episode_length={length}", f"clock={clock}", f"run_dir={_run(root)}"]

    def resume(root: Path) -> list[str]:
        return _again(start(root), ["run", f"resume={_run(root)}", "display=plain"], "run/experiment.json")(root)

    return Target(
        name=f"experiment_{clock}",
        span_s=span_s,
        planned=4,
        start=start,
        resume=resume,
        series="run/series/*",
        runs=lambda root: [_run(root)],
        expected=lambda root: _planned(_run(root)),
    )


def _serve_team(root: Path, port: int = 0) -> None:
    """examples/remote_team.py on `port` (0: a free one) in a session of its own; its pid and address in
    TEAM_FILE."""
    proc = subprocess.Popen(
        [sys.executable, str(ROOT / "examples" / "remote_team.py"), str(port)],
        stdout=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    line = proc.stdout.readline() if proc.stdout else ""  # "remote team on http://127.0.0.1:PORT"
    assert line.startswith("remote team on http"), f"the team server did not start: {line!r}"
    (root / TEAM_FILE).write_text(json.dumps({"pid": proc.pid, "url": line.split()[-1]}))


def _team(root: Path) -> dict:
    return json.loads((root / TEAM_FILE).read_text())


def _team_process(root: Path, kind: str) -> psutil.Process | None:
    if kind != TEAM or not (root / TEAM_FILE).exists():
        return None
    try:
        return psutil.Process(_team(root)["pid"])
    except psutil.NoSuchProcess:
        return None


def _restart_team(root: Path, kind: str) -> None:
    _serve_team(root, int(_team(root)["url"].rsplit(":", 1)[1]))


def _stop_team(root: Path) -> None:
    team = _team_process(root, TEAM)
    if team is not None:
        team.kill()
        psutil.wait_procs([team], timeout=10)


def remote(launcher: str, span_s: float) -> Target:
    """A remote team against do_nothing and balanced on the lockstep clock (its calls hold the world),
    the series on `launcher`; a seed may kill the team's server too."""
    ray = [f"launcher={launcher}"] if launcher != "local" else []

    def start(root: Path) -> list[str]:
        url = f"experiment.team_options.url={_team(root)['url']}"
        return ["run", *REMOTE, url, *ray, "episode_length=10", "clock=lockstep", f"run_dir={_run(root)}"]

    def resume(root: Path) -> list[str]:
        again = ["run", f"resume={_run(root)}", "display=plain", *ray]
        return _again(start(root), again, "run/experiment.json")(root)

    return Target(
        name="remote_lockstep" if launcher == "local" else f"remote_{launcher}_lockstep",
        span_s=span_s,
        planned=4,
        start=start,
        resume=resume,
        series="run/series/*",
        runs=lambda root: [_run(root)],
        expected=lambda root: _planned(_run(root)),
        prepare=_serve_team,
        kinds=(*KINDS, TEAM),
        outside=_team_process,
        revive=_restart_team,
        cleanup=_stop_team,
        lingering=RAY_AGENTS if launcher == "ray" else (),
    )


def compare_used(run: Path) -> dict[Path, int]:
    """Each series of a compare and the episodes it uses: those of the pairs the test decided on (an
    unkilled run stops at the same pair, and plays no episode past it)."""
    from pillagerbench.experiments.comparison import pair_scores, read

    c = read(run)
    if c is None:
        return {}
    needed = dict.fromkeys(c.series(), 0)
    for k in range(len(pair_scores(c, run))):
        a, b, i = c.pair(k)
        needed[a], needed[b] = max(needed[a], i + 1), max(needed[b], i + 1)
    return {run / "series" / sid: n for sid, n in needed.items()}


def compare_finished(root: Path) -> list[str]:
    """A compare ends with its answer: the test decided, or its cap's pairs all played."""
    from pillagerbench.experiments.comparison import answer, read

    c = read(_run(root))
    if c is None:
        return ["no compare.json: the compare never started"]
    found = answer(c, _run(root))
    return [] if found.finished else [f"the compare did not finish: {found.line()}"]


def compare(length: int, span_s: float) -> Target:
    def start(root: Path) -> list[str]:
        return ["compare", *COMPARE, f"episode_length={length}", "clock=lockstep", f"run_dir={_run(root)}"]

    def resume(root: Path) -> list[str]:
        return _again(start(root), ["compare", f"resume={_run(root)}"], "run/compare.json")(root)

    return Target(
        name="compare_lockstep",
        span_s=span_s,
        planned=4,
        start=start,
        resume=resume,
        series="run/series/*",
        runs=lambda root: [_run(root)],
        expected=lambda root: compare_used(_run(root)),
        finished=compare_finished,
    )


def _rounds(root: Path) -> list[Path]:
    from pillagerbench.league.rounds import round_dirs

    return round_dirs(_league(root))


def _init_league(root: Path) -> None:
    from pillagerbench.league.cli import main

    assert main([str(_league(root)), "init", "scenarios=[mushroom_war]"]) == 0


def league(length: int, span_s: float) -> Target:
    def start(root: Path) -> list[str]:
        return ["league", str(_league(root)), "play", *LEAGUE, f"episode_length={length}", "clock=lockstep"]

    return Target(
        name="league_lockstep",
        span_s=span_s,
        planned=4,
        start=start,
        resume=start,  # `play` again finishes the unfinished round, then stops at the budget
        series="L/matches/round_*/series/*",
        runs=_rounds,
        expected=lambda root: {d: n for run in _rounds(root) for d, n in _planned(run).items()},
        prepare=_init_league,
    )


TARGETS = {
    t.name: t
    for t in (
        experiment("lockstep", 10, span_s=25),
        experiment("real", 5, span_s=25),
        compare(10, span_s=40),
        league(10, span_s=30),
        remote("local", span_s=20),
        remote("ray", span_s=40),
    )
}
