"""People in the config (config/people.py): refusals in one line, seats, entrant labels (no server)."""

from __future__ import annotations

import pytest

from pillagerbench.cli import commands as cli
from pillagerbench.config.schema import RunConfig
from pillagerbench.config.validate import load_run
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
        (["red=human", "humans.client=java"], "humans.client='java': input should be 'page' or 'minecraft'"),
        (
            ["red=human", "humans.client=minecraft", "clock=lockstep"],
            "clock=lockstep: people play on the real clock (red: Ryn, Raze); drop clock=lockstep or the humans",
        ),
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


def test_humans_client_minecraft_is_a_choice_of_the_config():
    assert load_run(["red=human", "humans.client=minecraft"]).humans.client == "minecraft"
    assert load_run(["red=human"]).humans.client == "page"  # the default: the page


def test_a_run_stored_before_humans_client_reads_as_the_page():
    stored = load_run(["red=human"]).stored()
    del stored["humans"]["client"]  # a manifest written before the key (stop 58's runs)
    assert RunConfig.of(stored).humans.client == "page"
