"""Play a match from a config: `play_match`, the one way, for every series (an experiment's, and the
one series of a plain `pillagerbench run`: experiments/plain_run.py), and the scenario a config plays.
Both take the typed configuration (config/schema.py RunConfig).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from pathlib import Path

from pillagerbench.config.compose import ConfigError
from pillagerbench.config.people import seats_of
from pillagerbench.config.schema import RunConfig
from pillagerbench.match import Match
from pillagerbench.people import People
from pillagerbench.people.client import Clients
from pillagerbench.people.gate import LoginGate
from pillagerbench.people.lobby import briefing_of
from pillagerbench.people.page import PageServer
from pillagerbench.players import PlayerError
from pillagerbench.rundir import EpisodeRecord, LastEpisode, RunDir
from pillagerbench.scenarios import Scenario, make_scenario
from pillagerbench.scenarios.layout import parse_layout
from pillagerbench.server import ArenaServer
from pillagerbench.server.process import MC_VERSION
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
    people = people_of(cfg, scenario)
    clients = Clients.of(people.seats) if people is not None and cfg.humans.client == "minecraft" else None
    people = None if clients is not None else people  # people on Minecraft clients have no page (docs/people.md)
    gate = (
        LoginGate(clients.names, lambda: (cfg.server.host, server.port or 0), cfg.server.host, cfg.humans.port)
        if clients
        else None
    )
    page = PageServer(people, list(scenario.primitives), cfg.server.host, cfg.humans.port) if people else None
    if people is not None:
        people.run_dir = str(rundir.path.resolve())  # the pages say where the results are once the run is over
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
        people=people,
        clients=clients,
    )
    match.last_records.update(last or {})
    try:
        await set_up(match)
        if page is not None and people is not None:
            print(f"people: open {await page.start()} to play", flush=True)
            await seat_people(match, people, cfg.humans.ready_timeout_s)
        if gate is not None and clients is not None:
            await seat_clients(match, clients, gate, cfg.humans.ready_timeout_s)
        await match.play_episodes(people.episodes(episodes) if people else episodes, on_episode)
    finally:
        if page is not None:
            await page.stop()
        await match.close()
        await server.stop()
        if gate is not None:  # after the server: its last words (the whistle) pass the gate before it closes
            await gate.stop()
        for llm in llms.values():
            await llm.aclose()


def people_of(cfg: RunConfig, scenario: Scenario) -> People | None:
    """The people of a match (config/people.py), or None when agents play every player."""
    teams = {s.key: cfg.side(s.key) for s in scenario.sides}
    seats = {k: seats_of(teams[k].name, teams[k].humans, list(s.player_names)) for k, s in zip(teams, scenario.sides)}
    if not any(seats.values()):
        return None
    people = People({k: v for k, v in seats.items() if v}, briefing_of(scenario, cfg.split))
    people.planned = cfg.episodes
    if cfg.split in (None, "paper"):  # the layout every episode is played on; else each episode's, as it starts
        people.show_layout(scenario)
    return people


async def seat_people(match: Match, people: People, timeout: float) -> None:
    """Wait until every person is ready; then each side's entrant names its people (human:NAME)."""
    if not await people.wait_ready(timeout):
        raise ConfigError(
            f"humans: not every person was ready within {timeout:g} s (humans.ready_timeout_s); no episode played"
        )
    for side, entrant in match.entrants.items():
        names = [s.person or "?" for s in people.seats.seats.values() if s.side == side]
        match.entrants[side] = entrant.with_people(names)


async def seat_clients(match: Match, clients: Clients, gate: LoginGate, timeout: float) -> None:
    """People on Minecraft clients (people/client.py): the address and names to join with; joining is being
    ready; each side's entrant names its people by the players' names (human:Ryn)."""
    names = ", ".join(f"{n} ({side})" for n, side in clients.side_of.items())
    print(f"people: join with a Minecraft Java {MC_VERSION} client at {await gate.start()} as {names}", flush=True)
    if not await clients.wait_joined(match.server, timeout):
        raise ConfigError(
            f"humans: not every person joined within {timeout:g} s (humans.ready_timeout_s); no episode played"
        )
    for side, entrant in match.entrants.items():
        match.entrants[side] = entrant.with_people([n for n, s in clients.side_of.items() if s == side])


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
