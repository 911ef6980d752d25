"""Run an experiment: its series in parallel (each its own match and arena server on a free
port), series that start from another's checkpoint after it, and resume after a crash or kill.

    pillagerbench run experiment=main_benchmark experiment.team=cot llm=openai parallel=4
    pillagerbench run experiment=main_benchmark experiment.team=cot llm=openai resume=runs/...   # finish it

Run directory:

    experiment.json      name, the experiment config, the command's overrides, every series (with its config)
    manifest.json        the top-level config, versions, git revision
    calibration.json     if calibration=PATH was given (σ_blue for the report)
    series/<id>/         one series directory each (experiments/series.py)

A series runs all its episodes in one place (one task of this process, or one Ray task), so
its team objects and what they learn persist from episode to episode.
"""

from __future__ import annotations

import asyncio
import shutil
import time
import traceback
from collections.abc import Awaitable, Callable
from pathlib import Path

from pillagerbench.config.compose import ConfigError
from pillagerbench.config.schema import RunConfig, RunnerConfig, default
from pillagerbench.experiments.progress import ExperimentProgress
from pillagerbench.experiments.series import run_series
from pillagerbench.experiments.spec import SeriesSpec, build_series, launch_order
from pillagerbench.host.machine import CHOOSE_PARALLEL
from pillagerbench.llm.spend import spend_lines
from pillagerbench.rundir import (
    ExperimentFile,
    RunDir,
    progress,
    read_series,
    write_experiment_file,
)
from pillagerbench.rundir.manifest import experiment_manifest
from pillagerbench.teams.entrant import labels_of

IGNORED_ON_RESUME = ("display",)  # config keys that may differ between a run and its resume
STOPPED = "stopped"  # a series' status when it stopped past outage_wait_s (experiments/outage.py)


def local_parallel(
    cfg: RunnerConfig, *, clock: str = "real", cpus: int | None = None, load: float | None = None
) -> tuple[int, str | None]:
    """Matches at once on this machine: the user's `parallel` if given, else the clock's choice
    (pillagerbench/host/machine.py: on the real clock as many as the measured headroom allows, on the
    lockstep clock as many as the cores run without slowing each other), with one line saying so when
    that is not the CPU count."""
    if cfg.parallel:
        return cfg.parallel, None
    choice = CHOOSE_PARALLEL[clock](cpus, load)
    return choice.parallel, (choice.explain() if choice.parallel != choice.cpus else None)


def clock_of(specs: list[SeriesSpec]) -> str:
    """The clock an experiment's series play on: lockstep when every one does, else real (whose
    choice of `parallel` holds back for lag)."""
    lockstep = bool(specs) and all(s.config.clock.mode == "lockstep" for s in specs)
    return "lockstep" if lockstep else "real"


def make_experiment_dir(cfg: RunConfig) -> Path:
    if cfg.run_dir:
        return Path(cfg.run_dir)
    return Path("runs") / f"{time.strftime('%Y-%m-%d_%H-%M-%S')}_{experiment_name(cfg)}"


def experiment_name(cfg: RunConfig) -> str:
    return str((cfg.experiment or {})["name"])


def write_experiment(run_dir: Path, config: RunnerConfig, argv: list[str], specs: list[SeriesSpec]) -> None:
    """experiment.json and manifest.json of a new experiment; `config`: its configuration (a RunConfig,
    or a league round's runner keys and experiment, a compare's experiment alone), stored as given."""
    assert config.experiment is not None, "an experiment's configuration names its experiment"
    run_dir.mkdir(parents=True, exist_ok=True)
    manifest = experiment_manifest(config, created=time.strftime("%Y-%m-%dT%H:%M:%S%z"))
    data = ExperimentFile(
        name=config.experiment["name"],
        created=manifest.created,
        experiment=config.experiment,
        overrides=list(argv),
        series=[s.to_dict() for s in specs],
    )
    write_experiment_file(run_dir, data)
    RunDir(run_dir).write_manifest(manifest)


def load_experiment(run_dir: Path) -> tuple[str, list[SeriesSpec], dict[str, Path]]:
    """The series of a run directory: an experiment's, or the one series of a plain `pillagerbench run`."""
    found = read_series(run_dir)
    if found is None:
        raise ConfigError(f"resume={run_dir}: not a run directory (no experiment.json or manifest.json)")
    name, series = found
    return name, [s for s, _ in series], {s.id: d for s, d in series}


def series_progress(spec: SeriesSpec, series_dir: Path):
    """A series' episodes so far against its plan (rundir/schedule.py: spoiled ones replayed)."""
    return progress(RunDir(series_dir).finished(), spec.episodes, spec.config.retries)


def _comparable(spec: SeriesSpec) -> dict:
    d = spec.to_dict()
    d["config"] = {k: v for k, v in d["config"].items() if k not in IGNORED_ON_RESUME}
    for key in ("scoring", "protocol", "retries", "outage_wait_s"):  # runs from before these keys: the defaults
        d["config"].setdefault(key, default(key))
    return d


def check_same(stored: list[SeriesSpec], rebuilt: list[SeriesSpec], run_dir: Path) -> None:
    if [s.id for s in stored] != [s.id for s in rebuilt]:
        raise ConfigError(
            f"resume={run_dir}: this command builds other series than the run has "
            f"({len(rebuilt)} vs {len(stored)}; first stored {stored[0].id}, first now {rebuilt[0].id}); "
            "run the same command as the first time, or leave out experiment=... to use the stored one"
        )
    for a, b in zip(stored, rebuilt):
        da, db = _comparable(a), _comparable(b)
        if da != db:
            keys = sorted(k for k in set(da) | set(db) if da.get(k) != db.get(k))
            if keys == ["config"]:
                keys = [
                    "config." + k
                    for k in sorted(set(da["config"]) | set(db["config"]))
                    if da["config"].get(k) != db["config"].get(k)
                ]
            raise ConfigError(
                f"resume={run_dir}: series {a.id} differs from the stored one in {', '.join(keys)}; "
                "run the same command as the first time"
            )


async def run_all(
    specs: list[SeriesSpec], dirs: dict[str, Path], parallel: int, launch: Callable[[SeriesSpec, Path], Awaitable[dict]]
) -> dict[str, dict]:
    """Run every unfinished series, at most `parallel` at once, each after the series it depends on."""
    results: dict[str, dict] = {}
    pending = {s.id: s for s in launch_order(specs)}
    for s in specs:
        if series_progress(s, dirs[s.id]).complete:
            results[s.id] = {"id": s.id, "status": "done", "played": 0}
            pending.pop(s.id)
    running: dict[asyncio.Future, SeriesSpec] = {}
    try:
        while pending or running:
            for sid, s in list(pending.items()):
                if len(running) >= parallel:
                    break
                blocked = [
                    d
                    for d in s.after
                    if results.get(d, {}).get("status") in ("error", "skipped", STOPPED)
                    or (d not in results and d not in pending and d not in {r.id for r in running.values()})
                ]
                if blocked:
                    results[sid] = {"id": sid, "status": "skipped", "error": f"needs series {', '.join(blocked)}"}
                    pending.pop(sid)
                elif all(results.get(d, {}).get("status") == "done" for d in s.after):
                    running[asyncio.ensure_future(launch(s, dirs[s.id]))] = pending.pop(sid)
            if not running:
                for sid in list(pending):  # nothing can start: a dependency that never finishes
                    results[sid] = {"id": sid, "status": "skipped", "error": "its dependencies cannot finish"}
                    pending.pop(sid)
                break
            done, _ = await asyncio.wait(running, return_when=asyncio.FIRST_COMPLETED)
            for fut in done:
                s = running.pop(fut)
                exc = fut.exception()
                if exc is None:  # a series that stopped past outage_wait_s is not done (experiments/outage.py)
                    results[s.id] = {**fut.result(), "status": STOPPED if "outage" in fut.result() else "done"}
                else:
                    text = "".join(traceback.format_exception(type(exc), exc, exc.__traceback__))
                    dirs[s.id].mkdir(parents=True, exist_ok=True)
                    where = RunDir(dirs[s.id]).series_error_path
                    where.write_text(text)
                    results[s.id] = {"id": s.id, "status": "error", "error": f"{type(exc).__name__}: {exc}"}
                    print(f"[{s.id}] series failed: {type(exc).__name__}: {exc} (see {where})", flush=True)
    finally:
        for fut in running:
            fut.cancel()
        if running:
            await asyncio.wait(running, timeout=30)
    return results


def local_launcher(run_dir: Path):
    async def launch(spec: SeriesSpec, series_dir: Path) -> dict:
        return await run_series(spec, series_dir, run_dir)

    return launch


async def execute(run_dir: Path, title: str, specs: list[SeriesSpec], dirs: dict[str, Path], cfg: RunnerConfig) -> dict:
    launcher = cfg.launcher
    closer = None
    if launcher == "local":
        parallel, why = local_parallel(cfg, clock=clock_of(specs))
        if why:
            print(why, flush=True)
        launch = local_launcher(run_dir)
    elif launcher == "ray":
        from pillagerbench.experiments.ray_launcher import RayLauncher

        ray_launcher = RayLauncher(cfg.ray_address)
        parallel = int(cfg.parallel or ray_launcher.cpus())
        launch, closer = ray_launcher.launch_factory(run_dir), ray_launcher.close
    else:
        raise ConfigError(f"launcher={launcher!r}: valid launchers are local, ray")
    length = specs[0].config.episode_length if specs else float(default("episode_length"))
    print(
        f"{title}: {len(specs)} series, {sum(s.episodes for s in specs)} episodes, {parallel} at once ({launcher})",
        flush=True,
    )
    try:
        with ExperimentProgress(
            run_dir,
            specs,
            title,
            parallel=parallel,
            mode=cfg.display,
            episode_length=length,
            dirs=dirs,
        ):
            return await run_all(specs, dirs, parallel, launch)
    finally:
        if closer:
            closer()


def check_series(specs: list[SeriesSpec], dirs: dict[str, Path] | None = None) -> None:
    """Before anything starts: each distinct series config checked whole (config/validate.py: teams, their
    options, LLM settings), then the preflight (match/preflight.py: every LLM and team server answers),
    but for the sides a resumed series (its directory in `dirs`) waits for (experiments/outage.py)."""
    from pillagerbench.config.schema import check
    from pillagerbench.config.validate import team_problems
    from pillagerbench.match import preflight

    seen: dict[str, None] = {}
    for s in specs:
        for line in team_problems(s.config):
            seen.setdefault(line, None)
    check(list(seen))
    waits = {s.id: waiting_sides(s.config, dirs[s.id]) for s in specs} if dirs else {}
    sides = [
        checked
        for s in specs
        for side, checked in zip(preflight.SIDES, preflight.sides_of(s.config))
        if side not in waits.get(s.id, {})
    ]
    preflight.check(sides)


def waiting_sides(cfg: RunConfig, series_dir: Path) -> dict[str, str]:
    """The sides a resumed series waits for before it plays on: those its last episode could not reach."""
    from pillagerbench.experiments.outage import unreachable

    finished = RunDir(series_dir).read_lenient()[0] if cfg.outage_wait_s > 0 else {}
    return unreachable(finished[max(finished)], cfg) if finished else {}


def outage_lines(results: dict[str, dict], specs: list[SeriesSpec], dirs: dict[str, Path], run_dir: Path) -> list[str]:
    """One line when series stopped past outage_wait_s: how many, what did not answer, resume."""
    from pillagerbench.experiments.outage import Stopped

    stopped = [(s, Stopped(**results[s.id]["outage"])) for s in specs if "outage" in results.get(s.id, {})]
    if not stopped:
        return []
    left = sum(s.episodes - p.used - p.given_up for s, _ in stopped for p in [series_progress(s, dirs[s.id])])
    first = min((o for _, o in stopped), key=lambda o: o.since)
    return [f"{len(stopped)} series stopped: " + first.line(run_dir, left)]


def lag_lines(specs: list[SeriesSpec], dirs: dict[str, Path], show: int = 10) -> list[str]:
    """The episodes played under lag (pillagerbench/host/machine.py): a count, then up to `show` of them."""
    hit = [
        (s.id, i, rec.lag_reason)
        for s in specs
        for i, rec in sorted(RunDir(dirs[s.id]).finished().items())
        if rec.lagged
    ]
    if not hit:
        return []
    lines = [f"{len(hit)} episode(s) played under lag (scores may be low; try a lower parallel=; docs/performance.md):"]
    lines += [f"  {sid} episode {i}: {why}" for sid, i, why in hit[:show]]
    if len(hit) > show:
        lines.append(f"  ... and {len(hit) - show} more (pillagerbench report lists all)")
    return lines


def spoiled_lines(done: list) -> list[str]:
    """What our faults cost the experiment: episodes spoiled (played again) and planned ones given up."""
    spoiled, given_up = sum(p.spoiled for p in done), sum(p.given_up for p in done)
    if not spoiled:
        return []
    line = f"{spoiled} episode(s) spoiled on our side (in no score; the report's Failures table lists them)"
    if given_up:
        line += f"; {given_up} planned episode(s) given up after every try: fewer episodes used (raise retries= for more tries)"
    return [line]


def main_experiment(cfg: RunConfig, argv: list[str]) -> int:
    """`pillagerbench run experiment=NAME ...` and `pillagerbench run resume=RUN_DIR ...`."""
    if cfg.resume:
        run_dir = Path(cfg.resume)
        title, specs, dirs = load_experiment(run_dir)
        if cfg.experiment is not None and title != "run":
            check_same(specs, build_series(cfg, argv), run_dir)
        check_series(specs, dirs)
        print(f"resuming {run_dir}", flush=True)
        if title == "run":  # a plain run: finished as it was started, with its display and summary
            from pillagerbench.experiments.plain_run import play_run

            return play_run(specs[0], dirs[specs[0].id], cfg)
    else:
        specs = build_series(cfg, argv)
        check_series(specs)
        run_dir = make_experiment_dir(cfg)
        if RunDir(run_dir).is_experiment():
            raise ConfigError(f"{run_dir} already holds an experiment; finish it with resume={run_dir}")
        write_experiment(run_dir, cfg, argv, specs)
        if cfg.calibration:
            shutil.copyfile(cfg.calibration, RunDir(run_dir).calibration_path)
        title, dirs = experiment_name(cfg), {s.id: RunDir(run_dir).series_dir(s.id) for s in specs}
    print(f"run directory: {run_dir}", flush=True)
    try:
        results = asyncio.run(execute(run_dir, title, specs, dirs, cfg))
    except KeyboardInterrupt:
        print(f"interrupted: finished episodes are kept; finish with resume={run_dir}")
        return 130
    errors = [r for r in results.values() if r["status"] in ("error", "skipped")]
    stopped = outage_lines(results, specs, dirs, run_dir)
    done = [series_progress(s, dirs[s.id]) for s in specs]
    print(
        f"{sum(p.used for p in done)}/{sum(s.episodes for s in specs)} episodes used; "
        f"{len(errors)} series failed or skipped" + (f" (finish with resume={run_dir})" if errors else "")
    )
    for line in spoiled_lines(done):
        print(line)
    for line in lag_lines(specs, dirs):
        print(line)
    ledgers = [(RunDir(dirs[s.id]).ledger_path, labels_of(s.config)) for s in specs]  # each side's entrant
    for line in spend_lines(ledgers):
        print(line)
    for line in stopped:
        print(line)
    print(f"run directory: {run_dir}")
    return 1 if errors or stopped else 0
