"""What follows a game besides the game master: the replay recording, the live view, the world's
log, the lag meter and the progress display. Each is a part with the same hooks, called by the game
loop (`game.py`) in order: `start` before the clock, `second` with each second's clean scores,
`stopped` right after the whistle stopped every player (before the final score), `whistle` with the
final score, and `abort` when the game failed."""

from __future__ import annotations

import asyncio
import json
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pillagerbench.config.registry import Registry
from pillagerbench.config.sides import SIDES
from pillagerbench.host.machine import lag_verdict
from pillagerbench.players import Player
from pillagerbench.replay.record import RECORDING, Recorder
from pillagerbench.rundir import EpisodeDir, EpisodeRecord
from pillagerbench.scenarios import Scenario
from pillagerbench.server.clock import CLOCK_EVENT, GameClock, RealClock
from pillagerbench.server.seams import Server
from pillagerbench.teams import Team


@dataclass
class Game:
    """One game being played: what its parts may read."""

    server: Server
    scenario: Scenario
    teams: dict[str, Team]
    players: dict[str, Player]
    rec: EpisodeRecord
    out: Path
    length: float
    clock: GameClock = field(default_factory=RealClock)  # game time (config `clock`; server/clock.py)
    start: float = 0.0  # the clock's now() when the game started
    wall_start: float = 0.0  # time.monotonic() then


class Part:
    """A part of a game: every hook does nothing unless the part needs it."""

    async def start(self, game: Game) -> None:
        pass

    def second(self, game: Game, t: int, scores: dict[str, float]) -> None:
        pass

    async def stopped(self, game: Game) -> None:
        pass

    async def whistle(self, game: Game, final: dict[str, float]) -> None:
        pass

    async def abort(self) -> None:
        pass


class Replay(Part):
    """The replay recording of the game (docs/replays.md); players tell it when programs start,
    fail and end (`program`)."""

    def __init__(self) -> None:
        self.recorder: Recorder | None = None

    def program(self, player: str, what: str, message: str | None = None) -> None:
        if self.recorder is not None:
            self.recorder.program(player, what, message)

    async def start(self, game: Game) -> None:
        sc = game.scenario
        header = {
            "scenario": sc.key,
            "title": sc.title,
            "episode": game.rec.episode,
            "length": game.length,
            "seed": game.rec.seed,
            "sides": {
                s.key: {"team": game.teams[s.key].name, "color": s.color, "players": s.player_names} for s in sc.sides
            },
            "extra_players": [p.name for p in sc.extra_players],
        }
        self.recorder = Recorder(game.server, game.out / RECORDING, header, box=sc.arena.box, clock=game.clock)
        await self.recorder.start()

    def second(self, game: Game, t: int, scores: dict[str, float]) -> None:
        if self.recorder is not None:
            self.recorder.score(t, scores)

    async def whistle(self, game: Game, final: dict[str, float]) -> None:
        recorder, self.recorder = self.recorder, None
        if recorder is not None:
            recorder.score(game.length, final)
            await recorder.stop(final)

    async def abort(self) -> None:
        recorder, self.recorder = self.recorder, None
        if recorder is not None:  # the recording ends where the game stopped
            try:
                await recorder.stop()
            except Exception:  # noqa: BLE001 - the server is gone; the file is closed by stop()
                pass


class LiveView(Part):
    """The scoreboard of the live view (`watch=PORT`), told without waiting: it never holds the game up."""

    @staticmethod
    def _tell(game: Game, **state: Any) -> None:
        if not getattr(game.server, "watch_url", None):
            return
        task = asyncio.ensure_future(game.server.watch(**state))
        task.add_done_callback(lambda t: t.cancelled() or t.exception())  # a view that fails changes nothing

    async def start(self, game: Game) -> None:
        sides = game.scenario.sides
        self._tell(
            game,
            center=[sum(s.center[i] for s in sides) / len(sides) for i in range(3)],
            title=game.scenario.title,
            episode=game.rec.episode,
            length=game.length,
            t=0,
            sides={s.key: game.teams[s.key].name for s in sides},
        )

    def second(self, game: Game, t: int, scores: dict[str, float]) -> None:
        self._tell(game, t=t, scores=scores)

    async def whistle(self, game: Game, final: dict[str, float]) -> None:
        self._tell(game, t=game.length, scores=final)


def count_refusals(events: list[dict]) -> dict[str, int]:
    """Refused actions per player (the server's `refused` events; see docs/fair-play.md)."""
    counts: dict[str, int] = {}
    for e in events:
        if e.get("event") == "refused":
            counts[e["player"]] = counts.get(e["player"], 0) + 1
    return counts


def in_moments(events: list[dict]) -> list[dict]:
    """On the lockstep clock every event names its game tick: the events of one tick are one moment of
    the game, and the order in which they reached us within it is the machine's, not the game's (a dig,
    and the game master's line about it). They are put in the order of their ticks, and within a tick in
    a fixed order of their contents, so that the same game gives the same log; those marked
    `after_whistle` (done while the players were being stopped, on the wall clock: not the game's) come
    last. Unstamped (real clock): as they came."""
    if not events or not all(isinstance(e.get("tick"), int) for e in events):
        return events
    return sorted(events, key=lambda e: (bool(e.get("after_whistle")), e["tick"], json.dumps(e, sort_keys=True)))


class WorldLog(Part):
    """Every event the server pushed during the game: world_events.jsonl, the chat everyone could read
    (chat.txt: "<player> message", game-master lines plain), and the refusals per player in the record."""

    def __init__(self) -> None:
        self.queue: asyncio.Queue | None = None
        self.server: Server | None = None

    async def start(self, game: Game) -> None:
        if game.server.control is None:
            raise RuntimeError("the arena server is not running")
        self.server, self.queue = game.server, game.server.control.subscribe()

    async def whistle(self, game: Game, final: dict[str, float]) -> None:
        queue, self.queue = self.queue, None
        if queue is None:
            return
        if game.server.control is not None:
            game.server.control.unsubscribe(queue)
        events = in_moments(
            [e for e in (queue.get_nowait() for _ in range(queue.qsize())) if e.get("event") != CLOCK_EVENT]
        )
        files = EpisodeDir(game.out)
        files.write_world_events(events)
        lines = [
            (f"<{e['player']}> " if e.get("player") else "") + str(e.get("message", ""))
            for e in events
            if e.get("event") == "chat"
        ]
        files.write_chat(lines)
        game.rec.refusals = count_refusals(events)

    async def abort(self) -> None:
        queue, self.queue = self.queue, None
        if queue is not None and self.server is not None and self.server.control is not None:
            self.server.control.unsubscribe(queue)


async def bot_lag(players: dict[str, Any], *, reset: bool = False) -> dict[str, dict | None]:
    """Each bot's physics-tick lag since the last reset (None for a bot that did not answer)."""
    names = list(players)
    got = await asyncio.gather(*(players[n].lag(reset=reset) for n in names), return_exceptions=True)
    return {n: (g if isinstance(g, dict) else None) for n, g in zip(names, got)}


class LagMeter(Part):
    """Was the game played under lag (pillagerbench/host/machine.py): the server's ticks per second and each
    bot's physics-tick lag over the game, and the verdict, in the record."""

    def __init__(self) -> None:
        self.first_tick = 0

    async def start(self, game: Game) -> None:
        await bot_lag(game.players, reset=True)
        self.first_tick = (await game.server.status())["tick"]

    async def stopped(self, game: Game) -> None:
        rec = game.rec
        rec.game_s = round(time.monotonic() - game.wall_start, 3)
        rec.server_tps = round(((await game.server.status())["tick"] - self.first_tick) / rec.game_s, 2)
        rec.bot_lag = await bot_lag(game.players)
        if game.clock.mode == "lockstep":  # every tick waited for every bot: lag cost no game time
            rec.lagged, rec.lag_reason = False, "none possible: clock=lockstep (each tick waited for every bot)"
        else:
            rec.lagged, rec.lag_reason = lag_verdict(rec.server_tps, rec.bot_lag)


class Progress(Part):
    """The clock and scores for a display (`on_tick`): each second, and the final score."""

    def __init__(self, on_tick: Callable[[dict], None]):
        self.on_tick = on_tick

    def second(self, game: Game, t: int, scores: dict[str, float]) -> None:
        self.on_tick({"episode": game.rec.episode, "t": t, "length": game.length, **scores})

    async def whistle(self, game: Game, final: dict[str, float]) -> None:
        self.on_tick({"episode": game.rec.episode, "t": game.length, "length": game.length, **final})


class Scoreboard(Part):
    """The scoreboard every team may read (`TeamContext.scores`): each side's score at each second, and the
    final score."""

    def __init__(self, contexts: dict):
        self.contexts = contexts  # side -> its TeamContext this episode

    def second(self, game: Game, t: int, scores: dict[str, float]) -> None:
        for ctx in self.contexts.values():
            ctx.scores = {k: scores[k] for k in SIDES if k in scores}

    async def whistle(self, game: Game, final: dict[str, float]) -> None:
        self.second(game, int(game.length), final)


# the parts that follow every game, in the order their hooks run (a game shown on a terminal adds
# Progress after them: it needs the display's callback)
PARTS: Registry[type[Part]] = Registry(
    "match part", {"world_log": WorldLog, "lag_meter": LagMeter, "replay": Replay, "live_view": LiveView}
)
