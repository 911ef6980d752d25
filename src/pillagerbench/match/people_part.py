"""The people's part of a game (docs/people.md): at the start the pages get the episode's map and each
person's player runs the person's run (people/relay.py), each second the pages get the score and the clock
and quiet pages' players stand still, at the whistle the pages are told."""

from __future__ import annotations

import asyncio
from collections.abc import Callable

from pillagerbench.match.parts import Game, Part
from pillagerbench.people import People


class PeoplePart(Part):
    def __init__(self, people: People, sink: Callable[[str, list], None]):
        self.people, self.sink = people, sink

    async def start(self, game: Game) -> None:
        self.people.show_layout(game.scenario)  # the episode's own layout under split=dev|test
        self.people.board = {"scores": {}, "episode": game.rec.episode, "length": game.length}
        self.people.begin(game.players, self.sink, game.length)

    def second(self, game: Game, t: int, scores: dict[str, float]) -> None:
        self.people.board = {**self.people.board, "scores": dict(scores), "t": t}
        task = asyncio.ensure_future(self.people.still())
        task.add_done_callback(lambda t: t.cancelled() or t.exception())

    async def stopped(self, game: Game) -> None:
        await self.people.end()

    async def whistle(self, game: Game, final: dict[str, float]) -> None:
        await self.people.end(final)

    async def abort(self) -> None:
        await self.people.end()
