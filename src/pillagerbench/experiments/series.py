"""Play one series (a match of consecutive episodes) so that it can be killed and resumed.

A plain `pillagerbench run` is a series too (experiments/plain_run.py): its run directory is the series
directory. A series directory holds the episodes, the teams' state after the last finished episode, kept
checkpoints and, in an experiment, its spec (`pillagerbench.rundir` owns its layout). Each episode is
committed one way (`_commit`): both teams' state saved, then its line in episodes.jsonl. On resume
everything of an unfinished episode is moved to discarded/, the teams are restored from the state
after the last finished episode, and the series goes on with the next episode. An episode spoiled on
our side (rundir/faults.py) is kept and another index is played in its place, up to `retries` times
per planned episode (rundir/schedule.py), so the series reaches its planned episodes. After an episode
in which a side could not reach its LLM provider or its team server, the match is ended and the series
waits for it (experiments/outage.py), then plays on in a fresh match, or stops past `outage_wait_s`.
"""

from __future__ import annotations

import shutil
from collections.abc import Callable, Iterable, Iterator
from dataclasses import asdict
from pathlib import Path
from typing import Any

from pillagerbench.config.schema import RunConfig
from pillagerbench.experiments.outage import Status, Stopped, Waiter, write_status
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
from pillagerbench.suite.version import current


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
    on_outage: Callable[[Status | None], None] | None = None,
) -> dict:
    """Play the unfinished episodes of a series (`watch`: the live view's port; `on_outage`: the waiting's
    live status, experiments/outage.py). Returns {"id", "finished", "failed", "played", "used", "spoiled",
    "given_up"}, and "outage" (a Stopped, as a dict) when the series stopped past `outage_wait_s`."""
    from pillagerbench.match.run import scenario_from_config
    from pillagerbench.rundir.manifest import match_manifest
    from pillagerbench.teams import team_from_config

    rundir = RunDir(series_dir)
    rundir.path.mkdir(parents=True, exist_ok=True)
    cfg = spec.config
    if not rundir.series_path.exists() and run_dir is not None and Path(run_dir) != rundir.path:
        write_series(rundir, spec)
    finished, discarded = rundir.recover()
    write_status(rundir.path, None)  # a killed run's wait
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
            rundir.write_manifest(match_manifest(cfg, scenario))
        else:
            rundir.note_resume(sorted(finished), discarded, current()["label"])
        before = len(finished)
        waiter = Waiter(cfg, rundir, label=f"[{spec.id}] ", say=say, show=on_outage)
        match = _Match(spec, cfg, rundir, scenario, teams, on_episode, on_tick, watch)
        stopped = await match.play_through(waiter)
        summary["played"] = len(rundir.finished()) - before
        if stopped:
            summary["outage"] = asdict(stopped)
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


class _Match:
    """A series' episodes played in matches: one, or one more after each outage waited out."""

    def __init__(
        self,
        spec: SeriesSpec,
        cfg: RunConfig,
        rundir: RunDir,
        scenario: Any,
        teams: dict,
        on_episode: Callable[[Any], None] | None,
        on_tick: Callable[[dict], None] | None,
        watch: int | None,
    ) -> None:
        self.spec, self.cfg, self.rundir, self.scenario, self.teams = spec, cfg, rundir, scenario, teams
        self.on_episode, self.on_tick, self.watch = on_episode, on_tick, watch
        self.held: EpisodeRecord | None = None  # an episode after which the series waits, not yet committed

    async def play_through(self, waiter: Waiter) -> Stopped | None:
        """Play to the end of the series, waiting out each outage; a Stopped when a wait ran out."""
        stopped = await waiter.again(self.rundir.finished())  # a resumed series stopped (or killed) waiting
        while stopped is None:
            self.held = None
            if progress(self.rundir.finished(), self.spec.episodes, self.cfg.retries).complete:
                return None  # (the last episode was held: no match to start)
            remaining = episodes_to_play(self.rundir, self.spec.episodes, self.cfg.retries)
            await self._play(self._until_held(remaining), lambda rec: self._done(rec, waiter))
            if self.held is None:
                return None
            stopped = await waiter.after(self.held, self._commit_held)
        return stopped

    def _until_held(self, indices: Iterator[int]) -> Iterator[int]:
        """The episodes to play, up to one after which the series waits (the match then ends)."""
        while self.held is None and (index := next(indices, None)) is not None:
            yield index

    def _done(self, rec: EpisodeRecord, waiter: Waiter) -> None:
        if waiter.holds(rec):
            self.held = rec  # committed after the probe (Waiter.after), with what it found
        else:
            self.commit(rec)

    def commit(self, rec: EpisodeRecord) -> None:
        _commit(self.spec, self.rundir, self.teams, rec)
        if self.on_episode:
            self.on_episode(rec)

    def _commit_held(self, rec: EpisodeRecord) -> None:
        self.rundir.write_episode(rec)  # episode.json as the line says (a provider outage marked on it)
        self.commit(rec)

    async def _play(self, remaining: Iterable[int], done: Callable[[EpisodeRecord], None]) -> None:
        from pillagerbench.match.run import play_match

        finished = self.rundir.finished()
        ok = [i for i in sorted(finished) if finished[i].ok]
        # what the teams saw of the last episode (before a kill or an outage's wait), as if uninterrupted
        last = {side: self.rundir.last_seen(finished[ok[-1]]) for side in self.teams} if ok else {}
        live = LiveWriter(self.rundir.write_live)

        def tick(status: dict) -> None:
            live(status)
            if self.on_tick:
                self.on_tick(status)

        try:
            await play_match(
                self.cfg,
                self.rundir,
                self.scenario,
                self.teams,
                remaining,
                done,
                on_tick=tick,
                last=last,
                log_path=self.rundir.free_server_log(),
                watch=self.watch,
            )
        finally:
            self.rundir.live_path.unlink(missing_ok=True)


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
