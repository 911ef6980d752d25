"""`pillagerbench run` without experiment=: one match, played as a one-series experiment.

    pillagerbench run scenario=mushroom_war red=passive blue=balanced episodes=3 episode_length=120
    pillagerbench run resume=RUN_DIR     # after a kill: the rest of it, nothing lost, nothing repeated

The run directory (printed first and last) is the series' directory (experiments/series.py):
manifest.json, episodes.jsonl (one line per finished episode), per episode its events, score
timeline, game-master log and team artefacts, and state/ (both teams' state after the last finished
episode). Each episode is committed as a series' is: the teams' state first, its line last, so a run
killed at any moment resumes from its last finished episode. An episode that fails (a bot or the
server dies) is recorded as failed and the match goes on; Ctrl-C ends the match cleanly, keeping
every finished episode.
"""

from __future__ import annotations

import asyncio
import time
from pathlib import Path

from pillagerbench.config.schema import RunConfig
from pillagerbench.config.sides import SIDES
from pillagerbench.experiments.display import MatchDisplay
from pillagerbench.experiments.outage import Stopped
from pillagerbench.experiments.series import run_series
from pillagerbench.llm.spend import spend_lines
from pillagerbench.match.run import scenario_from_config
from pillagerbench.rundir import RunDir, SeriesSpec, plain_series, progress
from pillagerbench.teams.entrant import labels_of


def make_run_dir(cfg: RunConfig) -> Path:
    if cfg.run_dir:
        return Path(cfg.run_dir)
    stamp = time.strftime("%Y-%m-%d_%H-%M-%S")
    return Path("runs") / f"{stamp}_{cfg.scenario.name}_{cfg.red.name}_vs_{cfg.blue.name}"


def run_match(cfg: RunConfig) -> int:
    """A new plain run from the command's config."""
    run_dir = make_run_dir(cfg)
    return play_run(plain_series(cfg.for_series(), run_dir.name), run_dir, cfg)


def play_run(spec: SeriesSpec, run_dir: Path, cfg: RunConfig) -> int:
    """Play the unfinished episodes of a plain run (all of a new one) with its display, then its
    summary over every finished episode. `cfg`: the command's (display, watch)."""
    run_dir.mkdir(parents=True, exist_ok=True)
    print(f"run directory: {run_dir}", flush=True)
    try:
        summary = asyncio.run(_play(spec, run_dir, cfg))
    except KeyboardInterrupt:
        print(
            f"interrupted: finished episodes are kept in {RunDir(run_dir).episodes_path}; finish with resume={run_dir}"
        )
        print(f"run directory: {run_dir}")
        return 130
    records = RunDir(run_dir).records()
    failed = sum(r.status != "ok" for r in records)
    problems, all_without_model = summarize_problems(records)
    print(f"{len(records)} episode(s), {failed} failed")
    retries = spec.config.retries
    done = progress(RunDir(run_dir).finished(), spec.episodes, retries)
    if done.spoiled:
        print(
            f"{done.used} of {spec.episodes} planned episode(s) used; {done.spoiled} spoiled on our side "
            f"(in no score, played again up to retries={retries})"
            + (f"; {done.given_up} given up" if done.given_up else "")
        )
    for line in problems:
        print(line)
    for line in summarize_lag(records):
        print(line)
    for line in spend_lines([(RunDir(run_dir).ledger_path, labels_of(spec.config))]):
        print(line)
    if "outage" in summary:  # stopped past outage_wait_s (experiments/outage.py)
        print(Stopped(**summary["outage"]).line(run_dir, spec.episodes - done.used - done.given_up))
    print(f"run directory: {run_dir}")
    return 1 if (failed and failed == len(records)) or all_without_model or "outage" in summary else 0


async def _play(spec: SeriesSpec, run_dir: Path, cfg: RunConfig) -> dict:
    scenario = scenario_from_config(spec.config)
    title = f"{scenario.title}: red {spec.red} vs blue {spec.blue}"
    with MatchDisplay(title, cfg.display) as display:
        return await run_series(
            spec,
            run_dir,
            on_episode=display.episode_done,
            on_tick=display.tick,
            watch=cfg.watch,
            on_outage=display.outage,
        )


def summarize_problems(records: list) -> tuple[list[str], bool]:
    """Lines about episodes in which a team had problems (its model or its server never answered,
    ...), and whether every episode of some team went that way."""
    lines, all_failed = [], False
    for side in SIDES:
        hit = [r for r in records if side in (r.problems or {})]
        if hit:
            lines.append(
                f"{side} {getattr(hit[0], side)} had problems in {len(hit)} of {len(records)} "
                f"episode(s), e.g.: {hit[-1].problems[side][-1]}"
            )
            all_failed = all_failed or len(hit) == len(records)
    return lines, all_failed


def summarize_lag(records: list) -> list[str]:
    """One line per episode played under lag (pillagerbench/host/machine.py), after a count."""
    hit = [r for r in records if getattr(r, "lagged", False)]
    if not hit:
        return []
    return [f"{len(hit)} of {len(records)} episode(s) played under lag (scores may be low; docs/performance.md):"] + [
        f"  episode {r.episode}: {r.lag_reason}" for r in hit
    ]
