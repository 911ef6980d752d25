"""People in a match (docs/people.md). `Seating`: who plays each player (the team's agents, a person on
the page, a person on a Minecraft client). `PeoplePart`, the people's part of a game: at the start the pages
get the episode's map and each person's player runs the person's run (people/relay.py), each second the
pages get the score and the clock and quiet pages' players stand still, at the whistle the pages are told;
`ClientsPart`: the same for people playing from Minecraft clients (people/client.py)."""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from dataclasses import dataclass

from pillagerbench.match.parts import Game, Part
from pillagerbench.people import People
from pillagerbench.people.client import Clients
from pillagerbench.people.relay import whistle_line


@dataclass(frozen=True)
class Seating:
    """Who plays each player of a match: people on the page (`people`), people on Minecraft clients
    (`clients`: no bot), else the team's agents."""

    people: People | None = None
    clients: Clients | None = None

    def on_page(self, name: str) -> bool:
        return self.people is not None and name in self.people.seats.seats

    def on_client(self, name: str) -> bool:
        return self.clients is not None and name in self.clients.side_of

    def by_person(self, name: str) -> bool:
        """Whether a person plays `name`: its handle is a seat the team cannot drive."""
        return self.on_page(name) or self.on_client(name)

    def parts(self, sink: Callable[[str, list], None]) -> list[Part]:
        """The people's parts of a game (none without people)."""
        out: list[Part] = []
        if self.people is not None:
            out.append(PeoplePart(self.people, sink))
        if self.clients is not None:
            out.append(ClientsPart(self.clients))
        return out


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


class ClientsPart(Part):
    """The part of people playing from Minecraft clients (people/client.py): the game's start and the whistle
    told in their chat; each second a person back in the world is put where their player was."""

    def __init__(self, clients: Clients):
        self.clients = clients

    async def start(self, game: Game) -> None:
        await self._tell(game, f"the game is on: {game.length:g} s")

    def second(self, game: Game, t: int, scores: dict[str, float]) -> None:
        task = asyncio.ensure_future(self.clients.rejoined(game.players))
        task.add_done_callback(lambda t: t.cancelled() or t.exception())

    async def whistle(self, game: Game, final: dict[str, float]) -> None:
        await self._tell(game, whistle_line(final))

    async def _tell(self, game: Game, line: str) -> None:
        online = {p["name"] for p in await game.server.players()}
        for name in self.clients.names:
            if name in online:
                await game.server.tell(name, line)
