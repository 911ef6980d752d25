"""The relay's page state without a server (people/relay.py): the view's absence told, the chat a bot
heard kept per player with teammates' signals marked."""

from __future__ import annotations

from pillagerbench.people import People
from pillagerbench.players import PlayerError

MISSING = "Ryn: the first-person view needs the optional package prismarine-viewer (pillagerbench setup --watch)"


class _Channel:
    async def view(self) -> int:
        raise PlayerError(MISSING + "\n(more)")


class _Player:
    channel = _Channel()


async def test_a_page_is_told_why_there_is_no_view_and_sees_its_players_chat():
    people = People({"red": ["Ryn"]}, {"title": "t"})
    token = people.seats.take("alice", "Ryn").token
    people.players = {"Ryn": _Player()}  # type: ignore[dict-item]
    await people._view("Ryn")
    people._heard("Ryn", ["onChat", {"onChat": "<Raze> [Ryn signal]"}])
    people._heard("Ryn", ["onChat", {"onChat": "<Byte> hello"}])
    people._heard("Ryn", ["observe", {}])
    state = people.state(token)
    assert state["view"] == {"error": MISSING}
    assert state["chat"] == [{"text": "<Raze> [Ryn signal]", "signal": True}, {"text": "<Byte> hello", "signal": False}]
