"""One match: a series of episodes between two teams on one warm server.

Per episode: put the arena back in place, reset every player (position, empty inventory), pre-game
(not timed; duration recorded), game (`game.py`: wall clock, `episode_length` s: the game master's
rules run and every team's score is sampled each second; the parts of `parts.py` follow it),
whistle (all code stopped; the score at exactly the end is final), whether our machine stalled the
game (`_stalled`: the episode is then spoiled), post-game. The record of each
episode is written to the run directory (`pillagerbench.rundir`). The scorings: `scoring.py`.
"""

from __future__ import annotations

import asyncio
import functools
import json
import random
import time
from collections.abc import AsyncIterator, Callable
from contextlib import asynccontextmanager
from pathlib import Path
from typing import Any

from pillagerbench.config.schema import ClockConfig, default
from pillagerbench.config.sides import SIDES
from pillagerbench.llm import LLMClient
from pillagerbench.match.game import play_game
from pillagerbench.match.parts import PARTS, Game, Part, Progress, Replay, Scoreboard
from pillagerbench.match.people_part import Seating
from pillagerbench.match.player import RecordedPlayer
from pillagerbench.match.scoring import SCORINGS
from pillagerbench.match.sides_clock import SidesClock
from pillagerbench.people import People, SeatHandle
from pillagerbench.people.client import ClientPlayer, Clients
from pillagerbench.players import Player
from pillagerbench.rundir import EpisodeRecord, LastEpisode, RunDir, winner_of
from pillagerbench.rundir.entrant import Entrant
from pillagerbench.scenarios import Scenario, upstream
from pillagerbench.scenarios.layout import episode_layout
from pillagerbench.server.clock import GameClock, RealClock
from pillagerbench.server.seams import Server
from pillagerbench.teams import Team, TeamContext
from pillagerbench.teams.base import PlayerHandle


class Match:
    def __init__(
        self,
        server: Server,
        scenario: Scenario,
        teams: dict[str, Team],
        run_dir: Path,
        *,
        episode_length: float = default("episode_length"),
        seed: int = default("seed"),
        on_tick: Callable[[dict], None] | None = None,
        llms: dict[str, LLMClient] | None = None,
        scoring: str = default("scoring"),
        protocol: str = default("protocol"),
        step_wait_s: float | None = None,
        split: str | None = None,
        conditions: dict[str, Any] | None = None,
        entrants: dict[str, Entrant] | None = None,
        clock: ClockConfig | None = None,
        people: People | None = None,
        clients: Clients | None = None,
    ):
        SCORINGS.find(scoring)
        self.scoring, self.protocol = scoring, protocol
        # seconds of waiting before and after every run (None: upstream's with protocol=upstream, else 0)
        self.step_wait_s = upstream.step_wait_s(protocol) if step_wait_s is None else step_wait_s
        self.server, self.scenario, self.teams = server, scenario, teams
        self.llms = llms or {}  # side key -> LLM client of that team (LLM teams only)
        self.run_dir, self.episode_length, self.seed = Path(run_dir), float(episode_length), seed
        self.on_tick = on_tick
        self.entrants = entrants or {}  # side -> the entrant playing it (rundir/entrant.py), on every record
        self.players: dict[str, Player] = {}
        self.rundir = RunDir(run_dir)  # every path and record of the run directory
        self.last_records: dict[str, LastEpisode] = {}
        self.layout, self.split = scenario.layout_key, split  # split: each episode on a layout of its own
        self.conditions = dict(conditions or {})  # the rules differing from the suite's (suite/conditions.py)
        self.clock_config = clock or ClockConfig()  # config `clock`: what game time is
        self.clock: GameClock = RealClock()  # lockstep: the server's, from setup() on
        self.seating = Seating(people, clients)  # who plays each player: agents, people on the page or on clients

    def player_order(self, episode: int) -> list[str]:
        """The order the server visits players in during an episode: the sides' players interleaved,
        the side that goes first alternating by episode (red first in even episodes), then the
        scenario's extra players. No side is always first (see docs/fidelity.md, side symmetry)."""
        sides = list(self.scenario.sides)
        if episode % 2:
            sides.reverse()
        width = max(len(s.players) for s in sides)
        names = [s.players[i].name for i in range(width) for s in sides if i < len(s.players)]
        return names + [p.name for p in self.scenario.extra_players]

    async def setup(self) -> None:
        """Launch every player's bot at once, then log them in one at a time (the server handles logins
        best that way), sides interleaved."""
        if self.server.port is None:
            raise RuntimeError("the arena server is not running (start it before the match's setup)")
        port, log_dir = self.server.port, self.rundir.logs_dir()
        specs = {p.name: p for p in self.scenario.all_players()}
        players = [
            ClientPlayer(spec.name, self.server, spec.gamemode)
            if self.seating.on_client(spec.name)
            else Player(
                spec.name,
                port,
                server=self.server,
                log_dir=log_dir,
                primitives=list(self.scenario.primitives),
                clock=self.clock_config.mode,
                view=self.seating.on_page(spec.name),
            )
            for spec in (specs[n] for n in self.player_order(0))
        ]
        try:
            await asyncio.gather(*(p.launch() for p in players))
            for player in players:
                await player.start()
                self.players[player.name] = player
        except BaseException:
            await asyncio.gather(*(p.close() for p in players if p.name not in self.players), return_exceptions=True)
            raise
        await self.clock.end()
        if self.clock_config.mode == "lockstep":
            per_1k = self.clock_config.ticks_per_1k_tokens
            sides = {side.key: list(side.player_names) for side in self.scenario.sides}
            clock = SidesClock(self.server, self.server.control, per_1k, sides)
            await clock.start()
            self.clock = clock

    async def close(self) -> None:
        await asyncio.gather(*(p.close() for p in self.players.values()), return_exceptions=True)
        self.players.clear()
        await self.clock.close()

    async def play_episodes(self, episodes, on_episode: Callable[[EpisodeRecord], None]) -> None:
        """Play the given episode indices in order; after each, `on_episode(record)`. An episode that
        failed because the server died is followed by a fresh server and fresh logins."""
        for episode in episodes:
            rec = await self.play_episode(episode)
            on_episode(rec)
            if rec.status == "failed" and not self.server.alive:
                await self.restart()

    async def restart(self) -> None:
        """Every player logged out, the server started afresh, and every player logged in again."""
        await self.close()
        await self.server.stop()
        await self.server.start()
        await self.setup()

    def _parts(self) -> tuple[Replay, list[Part]]:
        """The parts that follow a game, in the order their hooks run."""
        parts: list[Part] = [cls() for cls in PARTS.values()]
        if self.on_tick is not None:
            parts.append(Progress(self.on_tick))
        return next(p for p in parts if isinstance(p, Replay)), parts

    async def play_episode(self, episode: int) -> EpisodeRecord:
        seed = self.seed * 1000 + episode
        key = episode_layout(self.layout, self.split, seed)
        if key != self.scenario.layout_key:  # the episode's own arena (players keep their names)
            self.scenario = self.scenario.with_layout(key)
        sc = self.scenario
        rec = EpisodeRecord(
            sc.key,
            self.teams["red"].name,
            self.teams["blue"].name,
            episode,
            seed=seed,
            scoring=self.scoring,
            protocol=self.protocol,
            layout=sc.layout_key,
            split=sc.split,
            conditions=dict(self.conditions),
            red_entrant=self.entrants.get("red"),
            blue_entrant=self.entrants.get("blue"),
        )
        out = self.rundir.episode(episode)
        episode_files = self.rundir.files(episode)
        episode_files.events_dir.mkdir(parents=True, exist_ok=True)
        files: dict[str, Any] = {}

        def sink(name: str, event: list) -> None:
            f = files.get(name) or files.setdefault(name, open(episode_files.player_events_path(name), "a"))
            f.write(json.dumps(event, default=str) + "\n")

        replay, parts = self._parts()
        t_start = time.monotonic()
        try:
            await self._play(rec, out, sink, replay, parts)
        except Exception as exc:  # noqa: BLE001 - one failed episode never ends the series
            rec.status, rec.error = "failed", f"{type(exc).__name__}: {exc}"
            for part in parts:
                await part.abort()
        finally:
            for f in files.values():
                f.close()
            rec.duration_s = round(time.monotonic() - t_start, 3)
            self.rundir.write_episode(rec)
        if rec.ok:  # what the teams see of it next episode: the record as written, as a resumed series reads it
            self.last_records = {key: self.rundir.last_seen(rec) for key in self.teams}
        return rec

    async def _reset(self, rec: EpisodeRecord) -> dict[str, list]:
        """The arena put back in place and every player reset; returns each player's observations."""
        sc = self.scenario
        await self.server.seed(rec.seed)
        rec.player_order = await self.server.player_order(self.player_order(rec.episode))
        t0 = time.monotonic()
        await sc.arena.build(self.server)
        await self.server.crop_growth(sc.crop_growth_chance, sc.random_tick_speed)
        names = [p.name for p in sc.all_players()]
        resets = (self.players[p.name].reset(position=p.spawn, inventory={}, seed=rec.seed) for p in sc.all_players())
        observations = dict(zip(names, await asyncio.gather(*resets)))
        for p in sc.all_players():
            if not self.seating.on_client(p.name):  # a client's is set by its reset, while its person is in the world
                await self.server.gamemode(p.name, p.gamemode)
        rec.reset_s = round(time.monotonic() - t0, 3)
        return observations

    def _handle(self, name: str, sink, rec: EpisodeRecord, replay: Replay) -> PlayerHandle:
        """The handle of a player for its team: a person's seat is not the team's to drive."""
        if self.seating.by_person(name):
            return SeatHandle(name, self.players[name].observe)
        return RecordedPlayer(
            self.players[name],
            sink,
            rec.runs,
            step_wait_s=self.step_wait_s,
            on_program=replay.program,
            clock=self.clock,
        )

    def _contexts(self, rec: EpisodeRecord, out: Path, sink, replay: Replay, observations: dict) -> dict:
        """Each side's TeamContext for this episode (its players' handles record their runs)."""
        contexts = {}
        for side in self.scenario.sides:
            team_dir = out / side.key
            team_dir.mkdir(exist_ok=True)
            handles: dict[str, PlayerHandle] = {n: self._handle(n, sink, rec, replay) for n in side.player_names}
            contexts[side.key] = TeamContext(
                scenario=self.scenario,
                side=side,
                episode=rec.episode,
                out_dir=team_dir,
                players=handles,
                observations={n: observations[n] for n in side.player_names},
                episode_length=self.episode_length,
                seed=rec.seed,
                llm=self.llms.get(side.key),
                last_episode=self.last_records.get(side.key, LastEpisode()),
                protocol=self.protocol,
                people=tuple(n for n in side.player_names if self.seating.by_person(n)),
            )
        return contexts

    async def _play(self, rec: EpisodeRecord, out: Path, sink, replay: Replay, parts: list[Part]) -> None:
        observations = await self._reset(rec)
        for llm in self.llms.values():
            llm.reset_episode()
        for team in self.teams.values():
            team.problems = []
        contexts = self._contexts(rec, out, sink, replay, observations)
        parts = [*parts, Scoreboard(contexts), *self.seating.parts(sink)]

        async def timed_pre_game(key):
            t = time.monotonic()
            await self.teams[key].pre_game(contexts[key])
            rec.pre_game_s[key] = round(time.monotonic() - t, 3)

        await asyncio.gather(*(timed_pre_game(k) for k in contexts))

        game = Game(self.server, self.scenario, self.teams, self.players, rec, out, self.episode_length, self.clock)
        for player in self.players.values():  # a restart before the game (its reset's) cost the game nothing
            player.bot.watchdog.take_stalls()
        async with self._game_time():
            clean, late = await play_game(game, contexts, random.Random(rec.seed), parts, self.scoring)
        self._stalled(rec)
        rec.scores = {"clean": {k: clean.timeline[-1][k] for k in SIDES}}
        if late:
            rec.scores["upstream"] = {k: late.timeline[-1][k] for k in SIDES}
        rec.red_score, rec.blue_score = rec.scores[self.scoring]["red"], rec.scores[self.scoring]["blue"]
        rec.winner = winner_of(rec.red_score, rec.blue_score)
        rec.iterations = {k: list(t.iterations) for k, t in self.teams.items()}
        await self._post_game(rec, contexts)

    @asynccontextmanager
    async def _game_time(self) -> AsyncIterator[None]:
        """The game on its clock: lockstep at its speed (between games it keeps real time's pace, so
        idle bots cost no CPU), each team's LLM calls holding the world while in flight."""
        clock = self.clock
        await clock.pace(self.clock_config.speed)
        await clock.begin(bystanders=[p.name for p in self.scenario.extra_players])
        for key, llm in self.llms.items():  # (on the real clock a hold and a charge are nothing)
            names = [s.player_names for s in self.scenario.sides if s.key == key][0]
            llm.thinking.during_game(
                functools.partial(clock.thinking, key), functools.partial(clock.charge, players=names)
            )
        try:
            yield
        finally:
            for llm in self.llms.values():
                llm.thinking.after_game()
            if self.server.alive:
                await clock.end()
                await clock.pace(1.0)

    async def _post_game(self, rec: EpisodeRecord, contexts: dict) -> None:
        """Each team looks back on what it saw; what went wrong for a team goes in the record."""
        for ctx in contexts.values():  # this episode's record so far (its post-game and duration still to come)
            ctx.last_episode = self.rundir.last_seen(rec)
        await asyncio.gather(*(self.teams[k].post_game(contexts[k]) for k in contexts))
        for key, llm in self.llms.items():
            problem = llm.budget.problem()
            if problem:
                rec.problems.setdefault(key, []).append(problem)
        for key, team in self.teams.items():
            if team.problems:
                rec.problems.setdefault(key, []).extend(team.problems)

    def _stalled(self, rec: EpisodeRecord) -> None:
        """Whether our machine stalled the game, and how (the episode is then spoiled: rundir/faults.py): on the
        lockstep clock the world went on without an idle bot at the server's wall-clock limit (a tick the wall
        clock chose; a seat's own `free` is no let-go), or a bot was restarted for the machine's sake (starved
        of CPU, or it did not stop in time: players/bot_process.py)."""
        reasons = self.clock.stalls(rec.problems)
        reasons += [stall for player in self.players.values() for stall in player.bot.watchdog.take_stalls()]
        if reasons:
            rec.stalled, rec.stall_reason = True, "; ".join(reasons)
