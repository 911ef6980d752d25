"""The seats people take: one per player a person plays (config/people.py), each taken by one page at a
time. A page gets a token when it takes a seat; the same token takes it back after the page was closed
(the player stood still meanwhile); another page is refused while the seat is taken."""

from __future__ import annotations

import secrets
import time
from dataclasses import dataclass

from pillagerbench.config.people import name_problem

GONE_S = 5.0  # a page silent this long has left its seat (closed, or its connection lost)


class Refused(Exception):
    """What a page asked for and may not have: one line, shown on the page."""


@dataclass
class Seat:
    side: str
    player: str  # the scenario's player the person plays
    person: str | None = None  # the name the person typed (their entrant: human:NAME)
    token: str | None = None
    ready: bool = False
    seen: float = 0.0  # time.monotonic() of the page's last request

    @property
    def connected(self) -> bool:
        return self.token is not None and time.monotonic() - self.seen < GONE_S

    def view(self) -> dict:
        return {
            "side": self.side,
            "player": self.player,
            "person": self.person,
            "ready": self.ready,
            "connected": self.connected,
        }


class Seats:
    def __init__(self, seats: dict[str, list[str]]):
        self.seats = {p: Seat(side, p) for side, players in seats.items() for p in players}

    def take(self, person: str, player: str | None = None) -> Seat:
        """A free seat (`player`'s, or the first free) for `person`; Refused when the name is not a player
        name, or the seat is another page's."""
        problem = name_problem(person)
        if problem:
            raise Refused(problem)
        if player is not None and player not in self.seats:
            raise Refused(f"{player!r} is not played by people here (seats: {', '.join(self.seats)})")
        free = [s for s in self.seats.values() if not s.connected and (player is None or s.player == player)]
        if not free:
            raise Refused(f"{player or 'every seat'} is taken: a second page for a taken player is refused")
        seat = free[0]
        seat.person, seat.token, seat.ready, seat.seen = person, secrets.token_hex(16), False, time.monotonic()
        return seat

    def of(self, token: str | None) -> Seat:
        """The seat a page's token holds (the page comes back into its player with it)."""
        for seat in self.seats.values():
            if token and seat.token == token:
                seat.seen = time.monotonic()
                return seat
        raise Refused("this page holds no seat (take one with your name)")

    def all_ready(self) -> bool:
        return all(s.ready for s in self.seats.values())

    def people(self, side: str) -> list[str]:
        """The names of the people playing `side`'s players, in the side's order."""
        return [s.person or "?" for s in self.seats.values() if s.side == side]
