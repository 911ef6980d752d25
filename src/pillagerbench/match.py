"""One match: a series of episodes between two teams on one warm server.

Per episode: put the arena back in place, reset every player (position, empty inventory), pre-game
(not timed; duration recorded), game (wall clock, `episode_length` s: the game master's rules run
and every team's score is sampled each second), whistle (all code stopped; the score at exactly
the end is final), post-game. The record of each episode is written to the run directory.

Scoring (config `scoring`, docs/fidelity.md): `clean` (the default) is the game master's score at
exactly the whistle. `upstream` reproduces upstream's numbers as well: play (and every player's
code) goes on past the whistle until upstream's "120 s" sample, the (L+1)-th line of a per-second
rewards file whose lines start UPSTREAM_WAIT_S + 1 s after the clock; the game master's
`upstream_scores` applies the scenario's own quirks (GameMaster). Such an episode records both
scores (`scores`), its headline `red_score`/`blue_score` being upstream's; the clean timeline stays
in timeline.json, upstream's samples go to timeline_upstream.json.
"""

from __future__ import annotations

import asyncio
import json
import random
import time
from collections.abc import Callable
from dataclasses import asdict
from pathlib import Path
from typing import Any

from pillagerbench.load import lag_verdict
from pillagerbench.players import Player
from pillagerbench.replay.record import RECORDING, Recorder
from pillagerbench.rundir import EpisodeRecord, LastEpisode, RunDir, winner_of
from pillagerbench.scenarios import Scenario
from pillagerbench.teams import Team, TeamContext

STOP_GRACE_S = 3.0
# upstream's judge started its code after an 80-tick wait (4 s) and wrote a rewards line each 1 s
# after that (the first one 1 s in), so line k (from 1) was written at 4 + k s; its analysis read
# line index L (k = L + 1): about L + 5 s after the clock started
UPSTREAM_WAIT_S = 4.0
# upstream's /step waited 80 ticks before each player's code and 80 after it (reference §1.4): with
# protocol=upstream every run of every team pays them (a restart costs 8 s; the first code starts 4 s in)
UPSTREAM_STEP_WAIT_S = 80 / 20
SCORINGS = ("clean", "upstream")


def count_refusals(events: list[dict]) -> dict[str, int]:
    """Refused actions per player (the server's `refused` events; see docs/fair-play.md)."""
    counts: dict[str, int] = {}
    for e in events:
        if e.get("event") == "refused":
            counts[e["player"]] = counts.get(e["player"], 0) + 1
    return counts


class RecordedPlayer:
    """A player handle that also appends every event of its runs to the episode's log, and tells
    the replay recording (when one is on) when each program starts, fails and ends."""

    def __init__(
        self,
        player: Player,
        sink: Callable[[str, list], None],
        runs: dict[str, int] | None = None,
        match: Match | None = None,
    ):
        self._player, self._sink, self._match = player, sink, match
        self._runs = {} if runs is None else runs  # code runs started per player this episode

    def __getattr__(self, name: str) -> Any:
        return getattr(self._player, name)

    def _program(self, what: str, message: str | None = None) -> None:
        recorder = self._match.recorder if self._match else None
        if recorder is not None:
            recorder.program(self._player.name, what, message)

    async def run(self, code: str, *, timeout: float | None = None, on_event=None) -> list:
        def both(event):
            self._sink(self._player.name, event)
            if isinstance(event, list) and event and event[0] == "onError":
                self._program("error", str((event[1] or {}).get("onError", "")) if len(event) > 1 else "")
            if on_event:
                on_event(event)

        wait = self._match.step_wait_s if self._match else 0.0
        if wait:
            await asyncio.sleep(wait)  # upstream's step: the wait before the code (cancelled at the whistle)
        self._runs[self._player.name] = self._runs.get(self._player.name, 0) + 1
        self._program("start")
        try:
            events = await self._player.run(code, timeout=timeout, on_event=both)
        finally:
            self._program("end")
        if wait:
            await asyncio.sleep(wait)  # and the wait after it, before the step returns
        return events


class Match:
    def __init__(
        self,
        server,
        scenario: Scenario,
        teams: dict[str, Team],
        run_dir: Path,
        *,
        episode_length: float = 120.0,
        seed: int = 0,
        on_tick: Callable[[dict], None] | None = None,
        llms: dict[str, Any] | None = None,
        scoring: str = "clean",
        protocol: str = "pillagerbench",
        step_wait_s: float | None = None,
    ):
        if scoring not in SCORINGS:
            raise ValueError(f"scoring={scoring!r}: valid: {', '.join(SCORINGS)}")
        self.scoring, self.protocol = scoring, protocol
        # seconds of waiting before and after every run (None: upstream's with protocol=upstream, else 0)
        self.step_wait_s = (
            (UPSTREAM_STEP_WAIT_S if protocol == "upstream" else 0.0) if step_wait_s is None else step_wait_s
        )
        self.server, self.scenario, self.teams = server, scenario, teams
        self.llms = llms or {}  # side key -> LLM client of that team (LLM teams only)
        self.run_dir, self.episode_length, self.seed = Path(run_dir), float(episode_length), seed
        self.on_tick = on_tick or (lambda status: None)
        self.players: dict[str, Player] = {}
        self.rundir = RunDir(run_dir)  # every path and record of the run directory
        self.last_records: dict[str, LastEpisode] = {}
        self.recorder: Recorder | None = None  # the replay recording of the game being played

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
        """Log every player in (one at a time: the server handles logins best that way), sides
        interleaved."""
        log_dir = self.run_dir / "logs"
        specs = {p.name: p for p in self.scenario.all_players()}
        for spec in (specs[n] for n in self.player_order(0)):
            player = Player(
                spec.name,
                self.server.port,
                server=self.server,
                log_dir=log_dir,
                primitives=list(self.scenario.primitives),
            )
            await player.start()
            self.players[spec.name] = player

    async def close(self) -> None:
        await asyncio.gather(*(p.close() for p in self.players.values()), return_exceptions=True)
        self.players.clear()

    async def play_episodes(self, episodes, on_episode: Callable[[EpisodeRecord], None]) -> None:
        """Play the given episode indices in order; after each, `on_episode(record)`. An episode that
        failed because the server died is followed by a fresh server and fresh logins."""
        for episode in episodes:
            rec = await self.play_episode(episode)
            on_episode(rec)
            if rec.status == "failed" and not self.server.alive:
                await self.close()
                await self.server.stop()
                await self.server.start()
                await self.setup()

    async def play_episode(self, episode: int) -> EpisodeRecord:
        sc = self.scenario
        rec = EpisodeRecord(
            sc.key,
            self.teams["red"].name,
            self.teams["blue"].name,
            episode,
            seed=self.seed * 1000 + episode,
            scoring=self.scoring,
            protocol=self.protocol,
        )
        out = self.rundir.episode(episode)
        out.mkdir(parents=True, exist_ok=True)
        events_dir = out / "events"
        events_dir.mkdir(exist_ok=True)
        files: dict[str, Any] = {}

        def sink(name: str, event: list) -> None:
            f = files.get(name) or files.setdefault(name, open(events_dir / f"{name}.jsonl", "a"))
            f.write(json.dumps(event, default=str) + "\n")

        t_start = time.monotonic()
        try:
            await self._play(rec, out, sink)
        except Exception as exc:  # noqa: BLE001 - one failed episode never ends the series
            rec.status, rec.error = "failed", f"{type(exc).__name__}: {exc}"
        finally:
            if self.recorder is not None:  # the game failed: the recording ends where it stopped
                recorder, self.recorder = self.recorder, None
                try:
                    await recorder.stop()
                except Exception:  # noqa: BLE001 - the server is gone; the file is closed by stop()
                    pass
            for f in files.values():
                f.close()
            rec.duration_s = round(time.monotonic() - t_start, 3)
            self.rundir.write_episode(rec)
        return rec

    async def _play(self, rec: EpisodeRecord, out: Path, sink) -> None:
        sc, rng = self.scenario, random.Random(rec.seed)
        await self.server.request("seed", seed=rec.seed)
        rec.player_order = await self.server.request("player_order", names=self.player_order(rec.episode))
        t0 = time.monotonic()
        await sc.arena.build(self.server)
        await self.server.request("crop_growth", chance=sc.crop_growth_chance, random_tick_speed=sc.random_tick_speed)
        observations = dict(
            zip(
                [p.name for p in sc.all_players()],
                await asyncio.gather(
                    *(self.players[p.name].reset(position=p.spawn, inventory={}) for p in sc.all_players())
                ),
            )
        )
        for p in sc.all_players():
            await self.server.request("gamemode", player=p.name, mode=p.gamemode)
        rec.reset_s = round(time.monotonic() - t0, 3)

        contexts = {}
        for llm in self.llms.values():
            llm.reset_episode()
        for team in self.teams.values():
            team.problems = []
        for side in sc.sides:
            team_dir = out / side.key
            team_dir.mkdir(exist_ok=True)
            contexts[side.key] = TeamContext(
                scenario=sc,
                side=side,
                episode=rec.episode,
                out_dir=team_dir,
                players={n: RecordedPlayer(self.players[n], sink, rec.runs, self) for n in side.player_names},
                observations={n: observations[n] for n in side.player_names},
                episode_length=self.episode_length,
                seed=rec.seed,
                llm=self.llms.get(side.key),
                last_episode=self.last_records.get(side.key, {}),
                protocol=self.protocol,
            )

        async def timed_pre_game(key):
            t = time.monotonic()
            await self.teams[key].pre_game(contexts[key])
            rec.pre_game_s[key] = round(time.monotonic() - t, 3)

        await asyncio.gather(*(timed_pre_game(k) for k in contexts))

        timeline, upstream = await self._game(rec, contexts, rng, out)
        rec.scores = {"clean": {k: timeline[-1][k] for k in ("red", "blue")}}
        if upstream:
            rec.scores["upstream"] = {k: upstream[-1][k] for k in ("red", "blue")}
        rec.red_score, rec.blue_score = rec.scores[self.scoring]["red"], rec.scores[self.scoring]["blue"]
        rec.winner = winner_of(rec.red_score, rec.blue_score)
        rec.iterations = {k: list(t.iterations) for k, t in self.teams.items()}
        for key, ctx in contexts.items():
            self.last_records[key] = self.rundir.last_seen(asdict(rec), timeline)
            ctx.last_episode = self.last_records[key]
        await asyncio.gather(*(self.teams[k].post_game(contexts[k]) for k in contexts))
        for key, llm in self.llms.items():
            problem = llm.budget.problem()
            if problem:
                rec.problems.setdefault(key, []).append(problem)
        for key, team in self.teams.items():
            if team.problems:
                rec.problems.setdefault(key, []).extend(team.problems)

    async def _bot_lag(self, *, reset: bool = False) -> dict[str, dict | None]:
        """Each bot's physics-tick lag since the last reset (None for a bot that did not answer)."""
        names = list(self.players)
        got = await asyncio.gather(*(self.players[n].lag(reset=reset) for n in names), return_exceptions=True)
        return {n: (g if isinstance(g, dict) else None) for n, g in zip(names, got)}

    @staticmethod
    def _write_world_events(queue: asyncio.Queue, out: Path) -> list[dict]:
        """world_events.jsonl: every event the server pushed during the game; chat.txt: the chat log
        everyone could read ("<player> message", game-master lines plain). Returns the events."""
        events = [queue.get_nowait() for _ in range(queue.qsize())]
        with open(out / "world_events.jsonl", "w") as f:
            for e in events:
                f.write(json.dumps(e) + "\n")
        lines = [
            (f"<{e['player']}> " if e.get("player") else "") + str(e.get("message", ""))
            for e in events
            if e.get("event") == "chat"
        ]
        (out / "chat.txt").write_text("\n".join(lines) + ("\n" if lines else ""))
        return events

    def _watch(self, **state: Any) -> None:
        """Tell the live view (`watch=PORT`) the scoreboard, without waiting: it never holds the game up."""
        if not getattr(self.server, "watch_url", None):
            return
        task = asyncio.ensure_future(self.server.request("watch", **state))
        task.add_done_callback(lambda t: t.cancelled() or t.exception())  # a view that fails changes nothing

    def _recorder(self, rec: EpisodeRecord, out: Path) -> Recorder:
        """The replay recording of this episode's game (docs/replays.md)."""
        sc = self.scenario
        header = {
            "scenario": sc.key,
            "title": sc.title,
            "episode": rec.episode,
            "length": self.episode_length,
            "seed": rec.seed,
            "sides": {
                s.key: {"team": self.teams[s.key].name, "color": s.color, "players": s.player_names} for s in sc.sides
            },
            "extra_players": [p.name for p in sc.extra_players],
        }
        return Recorder(self.server, out / RECORDING, header, box=sc.arena.box)

    async def _game(
        self, rec: EpisodeRecord, contexts: dict, rng: random.Random, out: Path
    ) -> tuple[list[dict], list[dict]]:
        """The game; returns the clean timeline (t = 0 … L) and, with scoring=upstream, upstream's
        samples (lines 0 … L of its rewards file)."""
        gm = self.scenario.game_master(self.server, rng)
        await gm.start()
        length = self.episode_length
        start = time.monotonic()
        deadline = start + length
        for ctx in contexts.values():
            ctx.deadline = deadline
            self.teams[ctx.side.key].iterations = []
        timeline: list[dict] = []
        upstream: list[dict] = []
        runs = rec.runs
        lock = asyncio.Lock()  # one game-master step at a time (the whistle's and the rules' own)
        over = asyncio.Event()  # the whistle, besides cancel(): Python 3.11's wait_for can swallow a cancel

        async def rules():
            while not over.is_set():
                await asyncio.sleep(gm.period_s)
                async with lock:
                    if not over.is_set():
                        await gm.step()

        async def sample_upstream():
            for line in range(int(length) + 1):
                t = UPSTREAM_WAIT_S + line + 1
                await asyncio.sleep(max(0.0, start + t - time.monotonic()))
                upstream.append({"t": t, "line": line, **await gm.upstream_scores(dict(runs))})

        async def sample():
            for second in range(int(length)):
                await asyncio.sleep(max(0.0, start + second - time.monotonic()))
                scores = await gm.scores()
                timeline.append({"t": second, **scores})
                recorder.score(second, scores)
                self._watch(t=second, scores=scores)
                self.on_tick({"episode": rec.episode, "t": second, "length": length, **scores})

        world = self.server.control.subscribe()  # what happened in the world, as the server saw it
        await self._bot_lag(reset=True)
        recorder = self.recorder = self._recorder(rec, out)
        await recorder.start()
        sides = self.scenario.sides
        self._watch(
            center=[sum(s.center[i] for s in sides) / len(sides) for i in range(3)],
            title=self.scenario.title,
            episode=rec.episode,
            length=length,
            t=0,
            sides={s.key: self.teams[s.key].name for s in sides},
        )
        first_tick = (await self.server.request("status"))["tick"]
        plays = [asyncio.create_task(self.teams[k].play(c), name=f"play-{k}") for k, c in contexts.items()]
        background = [asyncio.create_task(rules(), name="game-master"), asyncio.create_task(sample(), name="scores")]
        late = asyncio.create_task(sample_upstream(), name="upstream-scores") if self.scoring == "upstream" else None
        final: dict | None = None
        try:
            done, _ = await asyncio.wait(
                background + ([late] if late else []),
                timeout=max(0.0, deadline - time.monotonic()),
                return_when=asyncio.FIRST_EXCEPTION,
            )
            _raise_first(done)
            if late:  # upstream: the clean score at the whistle, then play on to upstream's sample
                async with lock:
                    await gm.step()
                    final = await gm.scores()
                done, _ = await asyncio.wait([late, background[0]], return_when=asyncio.FIRST_COMPLETED)
                _raise_first(done)
        finally:
            # the whistle: stop every player's code, then nothing a player does counts any more
            over.set()
            await asyncio.gather(*(p.stop() for p in self.players.values()), return_exceptions=True)
            tasks = plays + background + ([late] if late else [])
            for task in tasks:
                task.cancel()
            await asyncio.wait(tasks, timeout=STOP_GRACE_S)
        rec.game_s = round(time.monotonic() - start, 3)
        rec.server_tps = round(((await self.server.request("status"))["tick"] - first_tick) / rec.game_s, 2)
        rec.bot_lag = await self._bot_lag()
        rec.lagged, rec.lag_reason = lag_verdict(rec.server_tps, rec.bot_lag)
        if final is None:
            await gm.step()
            final = await gm.scores()
        recorder.score(length, final)
        self._watch(t=length, scores=final)
        self.recorder = None
        await recorder.stop(final)
        self.server.control.unsubscribe(world)
        rec.refusals = count_refusals(self._write_world_events(world, out))
        timeline.append({"t": length, **final})
        self.on_tick({"episode": rec.episode, "t": length, "length": length, **final})
        for task in plays:
            if task.done() and not task.cancelled() and task.exception():
                (out / f"{task.get_name()}.error.txt").write_text(repr(task.exception()))
        (out / "timeline.json").write_text(json.dumps(timeline))
        if late:
            (out / "timeline_upstream.json").write_text(json.dumps(upstream))
        (out / "game_master.json").write_text(json.dumps(gm.log))
        return timeline, upstream


def _raise_first(done: set[asyncio.Task]) -> None:
    for task in done:
        if not task.cancelled() and (exc := task.exception()) is not None:
            raise exc
