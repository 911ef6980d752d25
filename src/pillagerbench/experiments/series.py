"""Play one series (a match of consecutive episodes) so that it can be killed and resumed.

Layout of a series directory (a plain `pillagerbench run` directory plus):

    series.json                    the SeriesSpec (absent for a plain run)
    manifest.json, episodes.jsonl, episode_XXX/, llm_calls.jsonl, logs/, server*.log   as `pillagerbench run`
    state/episode_XXX/<side>/      both teams' state after the last finished episode (for resume)
    state/episode_XXX/ledger_offset  size of llm_calls.jsonl at the end of that episode
    checkpoints/episode_XXX/<side>/  checkpoints kept by the series' policy (team.json, ...)
    live.json                      the episode being played: clock and scores (progress display)
    discarded/                     half-written episodes (and their ledger lines) moved aside on resume

An episode is finished when its line is in episodes.jsonl; the line is written last, after the
episode's files and the teams' state. On resume everything of an unfinished episode is moved
to discarded/, the teams are restored from the state after the last finished episode, and the
series goes on with the next episode.
"""

from __future__ import annotations

import json
import os
import shutil
import time
from collections.abc import Callable
from dataclasses import asdict
from pathlib import Path
from typing import Any

from omegaconf import OmegaConf

from pillagerbench.experiments.layout import EPISODES, LEDGER, checkpoint_dir, episode_dir, episode_index, state_dir
from pillagerbench.experiments.spec import SeriesSpec


class ResumeError(RuntimeError):
    """A series directory that cannot be resumed as it was played."""


def read_finished(series_dir: Path) -> tuple[dict[int, dict], int, int]:
    """Finished episodes by index from episodes.jsonl, the byte length of its good lines, and its size."""
    path = Path(series_dir) / EPISODES
    if not path.exists():
        return {}, 0, 0
    data = path.read_bytes()
    finished: dict[int, dict] = {}
    good = 0
    for raw in data.splitlines(keepends=True):
        if not raw.endswith(b"\n"):
            break  # cut by a crash
        try:
            rec = json.loads(raw)
        except ValueError:
            break
        finished.setdefault(int(rec["episode"]), rec)
        good += len(raw)
    return finished, good, len(data)


def count_finished(series_dir: Path) -> int:
    return len(read_finished(series_dir)[0])


def _discard(series_dir: Path, path: Path, note: list[str]) -> None:
    target = Path(series_dir) / "discarded" / f"{path.name}.{time.strftime('%Y%m%d-%H%M%S')}"
    target.parent.mkdir(parents=True, exist_ok=True)
    shutil.move(str(path), str(target))
    note.append(f"{path.name} -> discarded/{target.name}")


def recover(series_dir: Path) -> tuple[dict[int, dict], list[str]]:
    """Make a series directory consistent after a crash; returns finished episodes and what was discarded."""
    series_dir = Path(series_dir)
    note: list[str] = []
    finished, good, size = read_finished(series_dir)
    if good < size:
        path = series_dir / EPISODES
        tail = path.read_bytes()[good:]
        (series_dir / "discarded").mkdir(exist_ok=True)
        (series_dir / "discarded" / f"episodes.tail.{time.strftime('%Y%m%d-%H%M%S')}").write_bytes(tail)
        with open(path, "r+b") as f:
            f.truncate(good)
        note.append(f"a torn last line of {EPISODES} ({len(tail)} bytes)")
    for d in sorted(series_dir.glob("episode_*")):
        i = episode_index(d.name)
        if d.is_dir() and i is not None and i not in finished:
            _discard(series_dir, d, note)
    for parent in (series_dir / "state", series_dir / "checkpoints"):
        for d in sorted(parent.glob("episode_*")) if parent.exists() else []:
            i = episode_index(d.name)
            if i is not None and i not in finished:
                shutil.rmtree(d, ignore_errors=True)
    ledger = series_dir / LEDGER
    if ledger.exists():
        offset = 0
        if finished:
            offset_file = state_dir(series_dir, max(finished)) / "ledger_offset"
            offset = (
                int(offset_file.read_text()) if offset_file.exists() else ledger.stat().st_size
            )  # older run: keep all
        if ledger.stat().st_size > offset:
            data = ledger.read_bytes()
            (series_dir / "discarded").mkdir(exist_ok=True)
            (series_dir / "discarded" / f"{LEDGER}.tail.{time.strftime('%Y%m%d-%H%M%S')}").write_bytes(data[offset:])
            with open(ledger, "r+b") as fh:
                fh.truncate(offset)
            calls = data[offset:].count(b"\n")
            note.append(f"{LEDGER}: {calls} call(s) of the unfinished episode")
    (series_dir / "live.json").unlink(missing_ok=True)
    return finished, note


def resolve_checkpoint(ref: dict, side: str, run_dir: Path | None) -> Path:
    if "path" in ref:
        return Path(ref["path"])
    if run_dir is None:
        raise ValueError(f"checkpoint {ref} names a series but the run directory is unknown")
    return checkpoint_dir(Path(run_dir) / "series" / ref["series"], int(ref["episode"]), ref.get("side", side))


def _append_line(path: Path, record: dict) -> None:
    with open(path, "a") as f:
        f.write(json.dumps(record) + "\n")
        f.flush()
        os.fsync(f.fileno())


def _write_json_atomic(path: Path, data: Any) -> None:
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(data))
    os.replace(tmp, path)


def _free_log_path(series_dir: Path) -> Path:
    path, n = series_dir / "server.log", 1
    while path.exists():
        path, n = series_dir / f"server.{n}.log", n + 1
    return path


async def run_series(
    spec: SeriesSpec,
    series_dir: Path,
    run_dir: Path | None = None,
    *,
    on_episode: Callable[[Any], None] | None = None,
    on_tick: Callable[[dict], None] | None = None,
    say: Callable[[str], None] = print,
) -> dict:
    """Play the unfinished episodes of a series. Returns {"id", "finished", "failed", "played"}."""
    from pillagerbench.arena import ArenaServer
    from pillagerbench.llm.presets import make_llms
    from pillagerbench.manifest import write_manifest
    from pillagerbench.match import Match
    from pillagerbench.scenarios import make_scenario
    from pillagerbench.teams import team_from_config

    series_dir = Path(series_dir)
    series_dir.mkdir(parents=True, exist_ok=True)
    cfg = OmegaConf.create(spec.config)
    if not (series_dir / "series.json").exists() and run_dir is not None and Path(run_dir) != series_dir:
        (series_dir / "series.json").write_text(
            json.dumps({k: v for k, v in spec.to_dict().items() if k != "config"}, indent=1)
        )
    finished, discarded = recover(series_dir)
    if discarded:
        say(f"[{spec.id}] resume: discarded {', '.join(discarded)}")
    remaining = [i for i in range(spec.episodes) if i not in finished]
    summary = {"id": spec.id, "played": 0}
    if remaining:
        scenario = make_scenario(cfg.scenario.name, crop_growth_chance=float(cfg.scenario.crop_growth_chance))
        teams = {"red": team_from_config(cfg.red, scenario.key), "blue": team_from_config(cfg.blue, scenario.key)}
        if finished:
            last = state_dir(series_dir, max(finished))
            for side, team in teams.items():
                if not (last / side / "team.json").exists():  # a learning team would start from scratch
                    raise ResumeError(
                        f"cannot resume: {side}'s state after episode {max(finished)} is missing "
                        f"({last / side / 'team.json'}); the team would forget what it learned"
                    )
                team.load_checkpoint(last / side)
            say(f"[{spec.id}] resume after {len(finished)} finished episode(s)")
        else:
            for side, ref in (spec.checkpoint or {}).items():
                teams[side].load_checkpoint(resolve_checkpoint(ref, side, run_dir))
        if not (series_dir / "manifest.json").exists():
            write_manifest(series_dir, cfg, scenario)
        else:
            _append_line(
                series_dir / "resumes.jsonl",
                {"ts": time.strftime("%Y-%m-%dT%H:%M:%S%z"), "finished": sorted(finished), "discarded": discarded},
            )
        await _play(
            spec,
            cfg,
            series_dir,
            scenario,
            teams,
            finished,
            remaining,
            on_episode,
            on_tick,
            ArenaServer,
            Match,
            make_llms,
        )
        summary["played"] = len(remaining)
    finished, _, _ = read_finished(series_dir)
    summary["finished"] = len(finished)
    summary["failed"] = sum(r.get("status") != "ok" for r in finished.values())
    return summary


async def _play(
    spec, cfg, series_dir, scenario, teams, finished, remaining, on_episode, on_tick, ArenaServer, Match, make_llms
) -> None:
    live = series_dir / "live.json"

    def tick(status: dict) -> None:
        _write_json_atomic(live, {**status, "ts": time.time()})
        if on_tick:
            on_tick(status)

    server = ArenaServer.from_config(cfg.server, log_path=_free_log_path(series_dir))
    await server.start()
    llms = make_llms(cfg, teams, series_dir)
    match = Match(
        server,
        scenario,
        teams,
        series_dir,
        episode_length=cfg.episode_length,
        seed=cfg.seed,
        on_tick=tick,
        llms=llms,
        scoring=cfg.get("scoring", "clean"),  # series of runs before these keys: the defaults
        protocol=cfg.get("protocol", "pillagerbench"),
    )
    ok = [i for i in sorted(finished) if finished[i].get("status") == "ok"]
    if ok:  # what the teams saw of the last episode before the kill
        from pillagerbench.match import last_episode_seen

        for side in teams:
            match.last_records[side] = last_episode_seen(finished[ok[-1]], episode_dir(series_dir, ok[-1]))
    try:
        await match.setup()

        def done(rec) -> None:
            _commit(spec, series_dir, teams, rec.episode, rec)
            if on_episode:
                on_episode(rec)

        await match.play_episodes(remaining, done)
    finally:
        live.unlink(missing_ok=True)
        await match.close()
        await server.stop()
        for llm in llms.values():
            await llm.aclose()


def _commit(spec: SeriesSpec, series_dir: Path, teams: dict, episode: int, rec) -> None:
    """Save state (and kept checkpoints), then the episodes.jsonl line that makes the episode finished."""
    state = state_dir(series_dir, episode)
    if state.exists():
        shutil.rmtree(state)
    for side, team in teams.items():
        team.save_checkpoint(state / side)
    ledger = series_dir / LEDGER
    (state / "ledger_offset").write_text(str(ledger.stat().st_size if ledger.exists() else 0))
    if spec.keeps_checkpoint(episode):
        for side in teams:
            target = checkpoint_dir(series_dir, episode, side)
            if target.exists():
                shutil.rmtree(target)
            shutil.copytree(state / side, target)
    _append_line(series_dir / EPISODES, asdict(rec))
    for old in (series_dir / "state").glob("episode_*"):
        i = episode_index(old.name)
        if i is not None and i < episode:
            shutil.rmtree(old, ignore_errors=True)
