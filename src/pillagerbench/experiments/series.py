"""Play one series (a match of consecutive episodes) so that it can be killed and resumed.

A plain `pillagerbench run` is a series too (experiments/plain_run.py): its run directory is the series
directory. A series directory holds the episodes, the teams' state after the last finished episode, kept
checkpoints and, in an experiment, its spec (`pillagerbench.rundir` owns its layout). Each episode is
committed one way (`_commit`): both teams' state saved, then its line in episodes.jsonl. On resume
everything of an unfinished episode is moved to discarded/, the teams are restored from the state
after the last finished episode, and the series goes on with the next episode. An episode spoiled on
our side (rundir/faults.py) is kept and another index is played in its place, up to `retries` times
per planned episode (rundir/schedule.py), so the series reaches its planned episodes.
"""

from __future__ import annotations

import shutil
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

from pillagerbench.config.schema import RunConfig
from pillagerbench.experiments.spec import SeriesSpec
from pillagerbench.rundir import (
    EpisodeRecord,
    LiveWriter,
    RunDir,
    episodes_to_play,
    has_team_state,
    progress,
    team_state_path,
    write_series,
)


class ResumeError(RuntimeError):
    """A series directory that cannot be resumed as it was played."""


def resolve_checkpoint(ref: dict, side: str, run_dir: Path | None) -> Path:
    if "path" in ref:
        return Path(ref["path"])
    if run_dir is None:
        raise ValueError(f"checkpoint {ref} names a series but the run directory is unknown")
    return RunDir(RunDir(run_dir).series_dir(ref["series"])).checkpoint(int(ref["episode"]), ref.get("side", side))


async def run_series(
    spec: SeriesSpec,
    series_dir: Path,
    run_dir: Path | None = None,
    *,
    on_episode: Callable[[Any], None] | None = None,
    on_tick: Callable[[dict], None] | None = None,
    say: Callable[[str], None] = print,
    watch: int | None = None,
) -> dict:
    """Play the unfinished episodes of a series (`watch`: the live view's port). Returns {"id",
    "finished", "failed", "played", "used", "spoiled", "given_up"}."""
    from pillagerbench.match.run import scenario_from_config
    from pillagerbench.rundir.manifest import write_manifest
    from pillagerbench.teams import team_from_config

    rundir = RunDir(series_dir)
    rundir.path.mkdir(parents=True, exist_ok=True)
    cfg = spec.config
    if not rundir.series_path.exists() and run_dir is not None and Path(run_dir) != rundir.path:
        write_series(rundir, spec)
    finished, discarded = rundir.recover()
    if discarded:
        say(f"[{spec.id}] resume: discarded {', '.join(discarded)}")
    retries = cfg.retries
    summary = {"id": spec.id, "played": 0}
    if not progress(finished, spec.episodes, retries).complete:
        scenario = scenario_from_config(cfg)
        teams = {"red": team_from_config(cfg.red, scenario.key), "blue": team_from_config(cfg.blue, scenario.key)}
        if finished:
            _restore(rundir, teams, max(finished))
            say(f"[{spec.id}] resume after {len(finished)} finished episode(s)")
        else:
            for side, ref in (spec.checkpoint or {}).items():
                teams[side].load_checkpoint(resolve_checkpoint(ref, side, run_dir))
        if not rundir.manifest_path.exists():
            write_manifest(rundir.path, cfg, scenario)
        else:
            rundir.note_resume(sorted(finished), discarded)
        before = len(finished)
        remaining = episodes_to_play(rundir, spec.episodes, retries)
        await _play(spec, cfg, rundir, scenario, teams, finished, remaining, on_episode, on_tick, watch)
        summary["played"] = len(rundir.finished()) - before
    finished = rundir.finished()
    done = progress(finished, spec.episodes, retries)
    summary.update(used=done.used, spoiled=done.spoiled, given_up=done.given_up)
    summary["finished"] = len(finished)
    summary["failed"] = sum(not r.ok for r in finished.values())
    return summary


def _restore(rundir: RunDir, teams: dict, episode: int) -> None:
    """Each team as it was after `episode` (its state saved then); a missing state is refused."""
    last = rundir.state(episode)
    for side, team in teams.items():
        if not has_team_state(last / side):  # a learning team would start from scratch
            raise ResumeError(
                f"cannot resume: {side}'s state after episode {episode} is missing "
                f"({team_state_path(last / side)}); the team would forget what it learned"
            )
        team.load_checkpoint(last / side)


async def _play(
    spec: SeriesSpec,
    cfg: RunConfig,
    rundir: RunDir,
    scenario,
    teams: dict,
    finished: dict[int, EpisodeRecord],
    remaining: Iterable[int],
    on_episode: Callable[[Any], None] | None,
    on_tick: Callable[[dict], None] | None,
    watch: int | None = None,
) -> None:
    from pillagerbench.match.run import play_match

    ok = [i for i in sorted(finished) if finished[i].ok]
    # what the teams saw of the last episode before the kill, as an uninterrupted series would
    last = {side: rundir.last_seen(finished[ok[-1]]) for side in teams} if ok else {}

    live = LiveWriter(rundir.write_live)

    def tick(status: dict) -> None:
        live(status)
        if on_tick:
            on_tick(status)

    def done(rec) -> None:
        _commit(spec, rundir, teams, rec)
        if on_episode:
            on_episode(rec)

    try:
        await play_match(
            cfg,
            rundir,
            scenario,
            teams,
            remaining,
            done,
            on_tick=tick,
            last=last,
            log_path=rundir.free_server_log(),
            watch=watch,
        )
    finally:
        rundir.live_path.unlink(missing_ok=True)


def _commit(spec: SeriesSpec, rundir: RunDir, teams: dict, rec) -> None:
    """Save state (and kept checkpoints), then the episodes.jsonl line that makes the episode finished."""
    state = rundir.state(rec.episode)
    if state.exists():
        shutil.rmtree(state)
    for side, team in teams.items():
        team.save_checkpoint(state / side)
    rundir.write_ledger_offset(rec.episode)
    if spec.keeps_checkpoint(rec.episode):
        for side in teams:
            target = rundir.checkpoint(rec.episode, side)
            if target.exists():
                shutil.rmtree(target)
            shutil.copytree(state / side, target)
    rundir.append(rec)
    for i, old in rundir.state_dirs():
        if i < rec.episode:
            shutil.rmtree(old, ignore_errors=True)
