"""`pillagerbench run`: play a match and record it.

    pillagerbench run scenario=mushroom_war red=passive blue=balanced episodes=3 episode_length=120

The run directory (printed first and last) holds manifest.json, episodes.jsonl (one line per
finished episode) and per episode its events, score timeline, game-master log and team artefacts.
An episode that fails (a bot or the server dies) is recorded as failed and the series goes on; one
spoiled on our side (rundir/faults.py) is kept, in no score, and played again as the next index up to
`retries` times (rundir/schedule.py), as in an experiment's series; Ctrl-C ends the match cleanly, keeping every finished episode.
"""

from __future__ import annotations

import asyncio
import time
from collections.abc import Callable, Iterable
from pathlib import Path

from pillagerbench.arena import ArenaServer
from pillagerbench.config import load_config
from pillagerbench.display import MatchDisplay
from pillagerbench.manifest import write_manifest
from pillagerbench.match import Match
from pillagerbench.rundir import EpisodeRecord, LastEpisode, RunDir, episodes_to_play, progress, retries_of
from pillagerbench.scenarios import Scenario, make_scenario
from pillagerbench.scenarios.layout import PAPER, parse_layout
from pillagerbench.teams import Team, team_from_config


def make_run_dir(cfg) -> Path:
    if cfg.run_dir:
        return Path(cfg.run_dir)
    stamp = time.strftime("%Y-%m-%d_%H-%M-%S")
    return Path("runs") / f"{stamp}_{cfg.scenario.name}_{cfg.red.name}_vs_{cfg.blue.name}"


async def play_match(
    cfg,
    rundir: RunDir,
    scenario: Scenario,
    teams: dict[str, Team],
    episodes: Iterable[int],
    on_episode: Callable[[EpisodeRecord], None],
    *,
    on_tick: Callable[[dict], None] | None = None,
    last: dict[str, LastEpisode] | None = None,
    log_path: Path | None = None,
    watch: int | None = None,
) -> None:
    """The one way to play a match from a config, for `run` and every series of an experiment: a
    server, the LLM clients, the match; the given episodes, `on_episode(record)` after each; then
    everything closed. `last`: what each side saw of its last episode (a resumed series)."""
    from pillagerbench.llm.presets import make_llms

    server = ArenaServer.from_config(cfg.server, log_path=log_path or rundir.free_server_log(), watch=watch)
    await server.start()
    if server.watch_url:
        print(f"live view: {server.watch_url}", flush=True)
    llms = make_llms(cfg, teams, rundir.path)
    match = Match(
        server,
        scenario,
        teams,
        rundir.path,
        episode_length=cfg.episode_length,
        seed=cfg.seed,
        scoring=cfg.get("scoring", "clean"),  # runs from before these keys: the defaults
        protocol=cfg.get("protocol", "pillagerbench"),
        split=cfg.get("split"),
        on_tick=on_tick,
        llms=llms,
    )
    match.last_records.update(last or {})
    try:
        await match.setup()
        await match.play_episodes(episodes, on_episode)
    finally:
        await match.close()
        await server.stop()
        for llm in llms.values():
            await llm.aclose()


def scenario_from_config(cfg) -> Scenario:
    """The scenario a config plays, on its `layout=` (`split=` chooses each episode's in the match)."""
    return make_scenario(
        cfg.scenario.name,
        layout=parse_layout(cfg.get("layout", PAPER)),
        crop_growth_chance=float(cfg.scenario.crop_growth_chance),
    )


async def play(cfg, run_dir: Path) -> list:
    scenario = scenario_from_config(cfg)
    teams = {"red": team_from_config(cfg.red, scenario.key), "blue": team_from_config(cfg.blue, scenario.key)}
    write_manifest(run_dir, cfg, scenario)
    rundir = RunDir(run_dir)
    records = []
    title = f"{scenario.title}: red {cfg.red.name} vs blue {cfg.blue.name}"
    with MatchDisplay(title, cfg.display) as display:

        def done(rec: EpisodeRecord) -> None:
            rundir.append(rec)
            records.append(rec)
            display.episode_done(rec)

        await play_match(
            cfg,
            rundir,
            scenario,
            teams,
            episodes_to_play(rundir, int(cfg.episodes), retries_of(cfg)),
            done,
            on_tick=display.tick,
            watch=cfg.get("watch"),
        )
    return records


def summarize_problems(records: list) -> tuple[list[str], bool]:
    """Lines about episodes in which a team had problems (its model or its server never answered,
    ...), and whether every episode of some team went that way."""
    lines, all_failed = [], False
    for side in ("red", "blue"):
        hit = [r for r in records if side in (r.problems or {})]
        if hit:
            lines.append(
                f"{side} {getattr(hit[0], side)} had problems in {len(hit)} of {len(records)} "
                f"episode(s), e.g.: {hit[-1].problems[side][-1]}"
            )
            all_failed = all_failed or len(hit) == len(records)
    return lines, all_failed


def summarize_lag(records: list) -> list[str]:
    """One line per episode played under lag (pillagerbench/machine.py), after a count."""
    hit = [r for r in records if getattr(r, "lagged", False)]
    if not hit:
        return []
    return [f"{len(hit)} of {len(records)} episode(s) played under lag (scores may be low; docs/performance.md):"] + [
        f"  episode {r.episode}: {r.lag_reason}" for r in hit
    ]


def main(argv: list[str]) -> int:
    """One match from Hydra overrides (`pillagerbench run` without experiment=/resume=, see cli.py)."""
    return run_match(load_config(argv))


def run_match(cfg) -> int:
    run_dir = make_run_dir(cfg)
    run_dir.mkdir(parents=True, exist_ok=True)
    print(f"run directory: {run_dir}", flush=True)
    try:
        records = asyncio.run(play(cfg, run_dir))
    except KeyboardInterrupt:
        print(f"interrupted: finished episodes are kept in {RunDir(run_dir).episodes_path}")
        print(f"run directory: {run_dir}")
        return 130
    failed = sum(r.status != "ok" for r in records)
    problems, all_without_model = summarize_problems(records)
    print(f"{len(records)} episode(s), {failed} failed")
    done = progress(RunDir(run_dir).finished(), int(cfg.episodes), retries_of(cfg))
    if done.spoiled:
        print(
            f"{done.used} of {cfg.episodes} planned episode(s) used; {done.spoiled} spoiled on our side "
            f"(in no score, played again up to retries={retries_of(cfg)})"
            + (f"; {done.given_up} given up" if done.given_up else "")
        )
    for line in problems:
        print(line)
    for line in summarize_lag(records):
        print(line)
    print(f"run directory: {run_dir}")
    return 1 if (failed and failed == len(records)) or all_without_model else 0
