"""Play a match from a config: `play_match`, the one way, for every series (an experiment's, and the
one series of a plain `pillagerbench run`: experiments/plain_run.py), and the scenario a config plays.
Both take the typed configuration (config/schema.py RunConfig).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from pathlib import Path

from pillagerbench.config.schema import RunConfig
from pillagerbench.match import Match
from pillagerbench.players import PlayerError
from pillagerbench.rundir import EpisodeRecord, LastEpisode, RunDir
from pillagerbench.scenarios import Scenario, make_scenario
from pillagerbench.scenarios.layout import parse_layout
from pillagerbench.server import ArenaServer
from pillagerbench.suite.conditions import conditions_of
from pillagerbench.teams import Team
from pillagerbench.teams.entrant import entrant_of


async def play_match(
    cfg: RunConfig,
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
    """The one way to play a match from a config, for every series (a plain run's too): a
    server, the LLM clients, the match; the given episodes, `on_episode(record)` after each; then
    everything closed. `last`: what each side saw of its last episode (a resumed series)."""
    from pillagerbench.llm.presets import make_llms

    server = ArenaServer.from_config(
        cfg.server, log_path=log_path or rundir.free_server_log(), watch=watch, clock=cfg.clock.mode
    )
    await server.start()
    if server.watch_url:
        print(f"live view: {server.watch_url}", flush=True)
        if cfg.clock.mode == "lockstep" and cfg.clock.speed == "max":
            print("live view: the lockstep clock runs unpaced (clock.speed=max); clock.speed=1 to watch", flush=True)
    llms = make_llms(cfg, teams, rundir.path)
    match = Match(
        server,
        scenario,
        teams,
        rundir.path,
        episode_length=cfg.episode_length,
        seed=cfg.seed,
        scoring=cfg.scoring,
        protocol=cfg.protocol,
        split=cfg.split,
        conditions=conditions_of(cfg.select, scenario.key),
        on_tick=on_tick,
        llms=llms,
        entrants={side: entrant_of(cfg, side) for side in teams},
        clock=cfg.clock,
    )
    match.last_records.update(last or {})
    try:
        await set_up(match)
        await match.play_episodes(episodes, on_episode)
    finally:
        await match.close()
        await server.stop()
        for llm in llms.values():
            await llm.aclose()


async def set_up(match: Match) -> None:
    """Log the match's players in. A login that fails (a bot that never spawned: ours, no team's
    fault, and no episode played yet) is tried once more on a fresh server before the series is
    given up."""
    try:
        await match.setup()
    except PlayerError as exc:
        print(f"login failed ({str(exc).splitlines()[0]}); once more on a fresh server", flush=True)
        await match.restart()


def scenario_from_config(cfg: RunConfig) -> Scenario:
    """The scenario a config plays, on its `layout=` (`split=` chooses each episode's in the match)."""
    return make_scenario(
        cfg.scenario.name,
        layout=parse_layout(cfg.layout),
        crop_growth_chance=cfg.scenario.crop_growth_chance,
    )
