"""People in the arena (docs/people.md): the page a person plays from (page.py), the seats people take
(seats.py), and the relay from the page to the person's player (relay.py)."""

from pillagerbench.people.relay import People, SeatHandle
from pillagerbench.people.seats import Refused, Seats

__all__ = ["People", "Refused", "SeatHandle", "Seats"]
