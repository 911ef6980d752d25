"""One game: the clock, the game master's rules, the scorings, the teams' play and the whistle; the
parts (`parts.py`) follow it through their hooks."""

from __future__ import annotations

import asyncio
import json
import random
import time

from pillagerbench.match.parts import Game, Part
from pillagerbench.match.scoring import CleanScoring, UpstreamScoring
from pillagerbench.rundir import EpisodeDir
from pillagerbench.scenarios.base import GameMaster
from pillagerbench.server.clock import GameClock
from pillagerbench.teams.base import TeamContext

STOP_GRACE_S = 3.0


async def play_game(
    game: Game, contexts: dict, rng: random.Random, parts: list[Part], scoring: str
) -> tuple[CleanScoring, UpstreamScoring | None]:
    """Play one game to the whistle (and, with scoring=upstream, on to upstream's last sample)."""
    clock = game.clock
    gm = game.scenario.game_master(game.server, rng)
    await gm.start()
    game.wall_start = time.monotonic()
    game.start = start = clock.now()
    deadline = start + game.length
    for ctx in contexts.values():
        ctx.deadline, ctx.clock = deadline, clock
        game.teams[ctx.side.key].iterations = []
    clean = CleanScoring()
    upstream = UpstreamScoring() if scoring == "upstream" else None
    lock = asyncio.Lock()  # one game-master step at a time (the whistle's and the rules' own)
    over = asyncio.Event()  # the whistle, besides cancel(): Python 3.11's wait_for can swallow a cancel

    async def rules():
        due = clock.now() + gm.period_s
        try:
            while not over.is_set():
                async with clock.at(due, "game-master"), lock:  # lockstep: at that tick exactly, the world held
                    if not over.is_set():
                        await gm.step()
                    due = clock.now() + gm.period_s  # a period after this step (its tick, on the lockstep clock)
        finally:
            await clock.let_go("game-master")

    def second(t: int, scores: dict) -> None:
        for part in parts:
            part.second(game, t, scores)

    for part in parts:
        await part.start(game)
    plays = [asyncio.create_task(_play(game, c, over), name=f"play-{k}") for k, c in contexts.items()]
    background = [
        asyncio.create_task(rules(), name="game-master"),
        asyncio.create_task(clean.sample(gm, clock, start, game.length, second), name="scores"),
    ]
    late = (
        asyncio.create_task(upstream.sample(gm, clock, start, game.length, game.rec.runs), name="upstream-scores")
        if upstream
        else None
    )
    whistle = asyncio.create_task(_whistle(clock, deadline), name="whistle")
    final: dict | None = None
    try:
        await _until(whistle, background + ([late] if late else []))
        if late or clock.mode == "lockstep":  # the score at the whistle (lockstep: at its tick, the world held)
            async with lock:
                final = await _score(gm)
        if late:  # upstream: play on to upstream's sample
            await clock.let_go("whistle")
            done, _ = await asyncio.wait([late, background[0]], return_when=asyncio.FIRST_COMPLETED)
            _raise_first(done)
    finally:
        # the whistle: stop every player's code, then nothing a player does counts any more
        over.set()
        await clock.end()  # lockstep: no call holds the world any more (the stops need its ticks)
        await asyncio.gather(*(p.stop() for p in game.players.values()), return_exceptions=True)
        tasks = plays + background + [whistle] + ([late] if late else [])
        for task in tasks:
            task.cancel()
        await asyncio.wait(tasks, timeout=STOP_GRACE_S)
    for part in parts:
        await part.stopped(game)
    if final is None:
        final = await _score(gm)
    for part in parts:
        await part.whistle(game, final)
    clean.final(game.length, final)
    for task in plays:
        if task.done() and not task.cancelled() and task.exception():
            EpisodeDir(game.out).task_error_path(task.get_name()).write_text(repr(task.exception()))
    clean.write(game.out)
    if upstream:
        upstream.write(game.out)
    EpisodeDir(game.out).game_master_path.write_text(json.dumps(gm.log))
    return clean, upstream


async def _score(gm: GameMaster) -> dict:
    """The score after one more step of the game master's."""
    await gm.step()
    return await gm.scores()


async def _whistle(clock: GameClock, deadline: float) -> None:
    """Wait for the whistle. On the lockstep clock the world is held at its tick until the score at the
    whistle is taken (`let_go`, or `end` drops it): taken while the world went on, it counted whatever
    the few ticks Python took on the wall clock brought (a Dash & Dine delivery: 498.2 or 599.0 points in
    two runs of one seed)."""
    async with clock.at(deadline, "whistle"):
        pass


async def _play(game: Game, ctx: TeamContext, over: asyncio.Event) -> None:
    """A team's play; once it is over (returned or failed) before the game is, its players rest to the
    game's end: on the lockstep clock an idle bot of a team that will never run it again would hold the
    world until the server lets go of it (5 s of wall time; scoring=upstream plays on past the whistle)."""
    try:
        await game.teams[ctx.side.key].play(ctx)
    finally:
        if not over.is_set():
            await game.clock.retire(list(ctx.side.player_names))


async def _until(whistle: asyncio.Task, tasks: list[asyncio.Task]) -> None:
    """Wait for the whistle; a task that fails first raises its exception at once."""
    waiting = set(tasks) | {whistle}
    while not whistle.done():
        done, waiting = await asyncio.wait(waiting, return_when=asyncio.FIRST_COMPLETED)
        _raise_first(done)


def _raise_first(done: set[asyncio.Task]) -> None:
    for task in done:
        if not task.cancelled() and (exc := task.exception()) is not None:
            raise exc
