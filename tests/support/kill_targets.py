"""The runs tests/support/kill_anywhere.py kills, as data: each a `Target` with its command, its resume, its
series directories and what an unkilled run of it uses. Short episodes of built-in teams, so a kill and
its resume take seconds: an experiment of 2 series x 2 episodes (lockstep 10 s, or real-clock 5 s), a
`compare` of passive and balanced against do_nothing under wide bounds, and a league's first round
(budget 4 episodes: one match and its side-swapped twin, 2 episodes each)."""

from __future__ import annotations

from pathlib import Path

from tests.support.kill_anywhere import Target

EXPERIMENT = [
    "experiment=round_robin_mushroom_war",
    "experiment.red_teams=[passive]",
    "experiment.blue_teams=[do_nothing,balanced]",
    "experiment.episodes=2",
    "parallel=2",
    "display=plain",
]
COMPARE = ["passive", "balanced", "opponent=do_nothing", "sprt.p1=0.9", "sprt.alpha=0.3", "sprt.beta=0.3", "cap=2"]
LEAGUE = ["budget.episodes=4", "episodes_per_match=2", "parallel=2", "display=plain"]


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
    )
}
