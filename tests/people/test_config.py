"""People in the config (config/people.py): refusals in one line, seats, entrant labels (no server)."""

from __future__ import annotations

import pytest

from pillagerbench.cli import commands as cli
from pillagerbench.people.seats import Refused, Seats
from pillagerbench.rundir.entrant import Entrant


@pytest.mark.parametrize(
    "args, expected",
    [
        (
            ["red=human", "clock=lockstep"],
            "clock=lockstep: people play on the real clock (red: Ryn, Raze); drop clock=lockstep or the humans",
        ),
        (["red=cot", "red.humans=[Ryn,Zed]"], "red.humans: 'Zed' is not a player of red (its players: Ryn, Raze)"),
        (["red=do_nothing", "red.humans=Ryn"], "red.humans='Ryn': a list of the side's players (one of Ryn, Raze)"),
        (["red=human", "humans.ready_timeout_s=0"], "humans.ready_timeout_s=0: input should be greater than 0"),
    ],
)
def test_bad_people_settings_are_one_line(args, expected, capsys):
    assert cli.main(["run", *args, "plan=true"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"pillagerbench run: {expected}"]


def test_a_seat_is_taken_once_and_a_bad_name_refused():
    seats = Seats({"red": ["Ryn", "Raze"]})
    with pytest.raises(Refused, match="not a player name"):
        seats.take("no way!", "Ryn")
    seat = seats.take("alice", "Ryn")
    with pytest.raises(Refused, match="a second page for a taken player is refused"):
        seats.take("mallory", "Ryn")
    assert seats.of(seat.token) is seat  # the page comes back into its player with its token
    assert seats.take("bob").player == "Raze"


def test_people_are_entrants_of_their_own():
    assert Entrant("human").with_people(["alice", "bob"]).label == "human:alice+human:bob"
    mixed = Entrant("cot", {"team": "gpt-4o"}).with_people(["alice"])
    assert mixed.label == "cot@gpt-4o+human:alice" and mixed != Entrant("cot", {"team": "gpt-4o"})
    assert Entrant.from_dict(mixed.to_dict()) == mixed
