"""`pillagerbench compare A B [opponent=O] [cap=PAIRS] [sprt.KEY=VALUE ...] [key=value ...]`: is entrant A
better than entrant B? Paired play and a sequential test that stops as soon as the answer is clear.

    pillagerbench compare passive balanced opponent=do_nothing       # each against do_nothing
    pillagerbench compare cot tacticrafter llm=openai llm.model=gpt-4o  # head to head
    pillagerbench compare resume=RUN_DIR                              # after a kill: on from where it was

A and B are team names (any registered team; the other keys, e.g. `scenario=`, `episode_length=`,
`llm=`, apply to both). Pairs of episodes on the same seeds (so the same layouts with `split=dev` or
the paper's): with an opponent, a pair is A against it and B against it on the same side, the next pair
on the other side; A scores 1 when its points beat B's (0.5 level, 0 behind). Head to head, a pair is A
red against B and B red against A; A scores its mean result (1 won, 0.5 drew, 0 lost). After each pair
the sequential test (stats/sprt.py; `sprt.p0` 0.5, `sprt.p1` 0.65, `sprt.alpha` 0.05, `sprt.beta` 0.05)
shows its log-likelihood ratio against its bounds; it ends with one line: A better, not better, or
undecided at the cap (`cap` pairs; default: as many as a fixed-size test of the same error rates needs),
with the episodes and dollars spent. The run directory is an experiment's (`report` reads it) with
`compare.json` beside it; a spoiled episode (our fault) is played again, as in any series.
"""

from __future__ import annotations

import asyncio
import time
from pathlib import Path

from pillagerbench.config.compose import ConfigError
from pillagerbench.config.schema import RunConfig, RunnerConfig
from pillagerbench.experiments.comparison import FILE, Answer, Comparison, answer, read, settle
from pillagerbench.experiments.outage import Stopped
from pillagerbench.experiments.runner import write_experiment
from pillagerbench.experiments.series import run_series
from pillagerbench.rundir import RunDir, SeriesSpec
from pillagerbench.stats.sample_size import fixed_test
from pillagerbench.stats.sprt import Bounds

OWN_KEYS = ("opponent", "cap", "resume", "run_dir", *(f"sprt.{k}" for k in ("p0", "p1", "alpha", "beta")))


def parse(argv: list[str]) -> tuple[Comparison | None, Path | None]:
    """The comparison a command line asks for (None with resume=: it is read from the run directory)."""
    names = [a for a in argv if "=" not in a]
    own = {k: v for k, _, v in (a.partition("=") for a in argv if "=" in a) if k in OWN_KEYS}
    game = [a for a in argv if "=" in a and a.partition("=")[0] not in OWN_KEYS]
    if own.get("resume"):
        if names or game or set(own) - {"resume"}:
            raise ConfigError("compare resume=RUN_DIR plays on as it was started: give nothing else")
        return None, Path(own["resume"])
    if len(names) != 2:
        raise ConfigError(f"two entrants to compare, A and B (team names), got {len(names)}: {' '.join(names)}")
    a, b = names
    if a == b:
        raise ConfigError(f"A and B are the same entrant ({a}); compare two different ones")
    try:
        bounds = Bounds(**{k.removeprefix("sprt."): float(v) for k, v in own.items() if k.startswith("sprt.")})
    except ValueError:
        raise ConfigError("sprt.p0, sprt.p1, sprt.alpha and sprt.beta are numbers") from None
    if bad := bounds.problems():
        raise ConfigError("; ".join(bad))
    cap = int(own.get("cap") or fixed_test(0.5, bounds.p1 - bounds.p0, bounds.alpha, bounds.beta))
    if cap < 1:
        raise ConfigError(f"cap={cap}: at least one pair")
    run_dir = Path(own["run_dir"]) if own.get("run_dir") else None
    return Comparison(a, b, own.get("opponent"), bounds, cap, game), run_dir


def configs(c: Comparison) -> dict[str, RunConfig]:
    """Each series' whole configuration, checked (one ConfigError line per problem, nothing played)."""
    from pillagerbench.config.validate import load_run

    cfgs = {sid: load_run([*c.game, f"red={red}", f"blue={blue}"]) for sid, (red, blue) in c.series().items()}
    for cfg in cfgs.values():
        if seated := cfg.seated():
            raise ConfigError(
                f"people would play {' and '.join(seated)} (team human or humans=): compare plays pair after "
                "pair as it decides, a fresh match each, and cannot seat people; play the person's episodes with "
                "`pillagerbench run` and another entrant's on the same seed and opponent, then `pillagerbench report "
                "RUN RUN` (differences.md; docs/people.md)"
            )
    return cfgs


def specs(c: Comparison, cfgs: dict[str, RunConfig]) -> list[SeriesSpec]:
    """The series, every one on the same seed (its episodes on the same layouts as the others')."""
    return [
        SeriesSpec(
            id=sid,
            index=i,
            design="compare",
            scenario=cfg.scenario.name,
            red=red,
            blue=blue,
            red_team=red,
            blue_team=blue,
            episodes=c.cap,
            seed=cfg.seed,
            config=cfg,
        )
        for i, ((sid, (red, blue)), cfg) in enumerate(zip(c.series().items(), cfgs.values(), strict=True))
    ]


def line(k: int, score: float, value: float, b: Bounds) -> str:
    return f"pair {k + 1}: A scores {score:g}; LLR {value:+.2f} in [{b.lower:+.2f}, {b.upper:+.2f}]"


class GaveUp(Exception):
    """A series of the compare stopped waiting for its provider or team server; the message says so."""


def play(c: Comparison, run_dir: Path, series: dict[str, SeriesSpec]) -> Answer:
    """Pairs until the test decides or the cap; prints a line per pair; returns the answer."""
    shown = 0
    while True:
        found = answer(c, run_dir)
        for k in range(shown, len(found.scores)):
            print(line(k, found.scores[k], found.path[k], c.bounds), flush=True)
        shown = len(found.scores)
        if found.finished:
            return found
        sa, sb, i = c.pair(len(found.scores))
        for sid in (sa, sb):
            spec = series[sid]
            spec.episodes = i + 1  # this series' results up to this pair
            summary = asyncio.run(run_series(spec, RunDir(run_dir).series_dir(sid), run_dir, say=print))
            if "outage" in summary:  # stopped past outage_wait_s (experiments/outage.py)
                raise GaveUp(Stopped(**summary["outage"]).line(run_dir, 1))


def start(c: Comparison, run_dir: Path | None) -> tuple[Path, dict[str, SeriesSpec]]:
    """A new compare's run directory (compare.json, experiment.json); refused where one exists."""
    from pillagerbench.match import preflight

    cfgs = configs(c)
    for cfg in cfgs.values():
        preflight.check(preflight.sides_of(cfg))
    stamp = time.strftime("%Y-%m-%d_%H-%M-%S")
    run_dir = run_dir or Path("runs") / f"{stamp}_compare_{c.a}_vs_{c.b}"
    if (run_dir / FILE).exists():
        raise ConfigError(f"{run_dir} holds a compare already: play on with compare resume={run_dir}")
    all_specs = specs(c, cfgs)
    experiment = RunnerConfig.model_validate({"experiment": {"name": f"compare {c.a} vs {c.b}", "design": "compare"}})
    write_experiment(run_dir, experiment, [c.a, c.b, *c.game], all_specs)
    c.write(run_dir)
    return run_dir, {s.id: s for s in all_specs}


def resume(run_dir: Path) -> tuple[Comparison, dict[str, SeriesSpec]]:
    c = read(run_dir)
    if c is None:
        raise ConfigError(f"resume={run_dir}: not a compare's run directory (no {FILE})")
    return c, {s.id: s for s in specs(c, configs(c))}


def main(argv: list[str]) -> int:
    c, run_dir = parse(argv)
    if c is None:
        assert run_dir is not None
        c, series = resume(run_dir)
    else:
        run_dir, series = start(c, run_dir)
    print(f"run directory: {run_dir}", flush=True)
    against = f"each against {c.opponent}" if c.opponent else "head to head"
    print(f"compare {c.a} (A) with {c.b} (B), {against}: up to {c.cap} pairs", flush=True)
    try:
        found = play(c, run_dir, series)
    except GaveUp as exc:
        print(f"compare: {exc}")
        return 1
    settle(run_dir, found)  # its series are finished: report, verify and export read them so
    print(found.line())
    return 0
