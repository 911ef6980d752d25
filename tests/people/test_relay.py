"""The relay's page state without a game (people/relay.py, people/page.py): the view's absence told, the
chat a bot heard kept per player with teammates' signals marked, the lobby's map of the layout played, the
signal button."""

from __future__ import annotations

import re

from starlette.testclient import TestClient

from pillagerbench.config.compose import load_config
from pillagerbench.config.schema import RunConfig
from pillagerbench.match.run import people_of, scenario_from_config
from pillagerbench.people import People
from pillagerbench.people.lobby import layout_page
from pillagerbench.people.page import app
from pillagerbench.players import PlayerError
from pillagerbench.scenarios import Scenario, make_scenario

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


def _page(*argv: str) -> tuple[People, TestClient, Scenario]:
    """The page server of a run configured by `argv` (a person plays Ryn), as the match makes it."""
    cfg = RunConfig.of(load_config(["red=do_nothing", "red.humans=[Ryn]", "blue=passive", *argv]))
    scenario = scenario_from_config(cfg)
    people = people_of(cfg, scenario)
    assert people is not None
    return people, TestClient(app(people, [])), scenario


def test_the_lobby_shows_the_map_of_the_layout_played():
    people, page, scenario = _page("layout=42")
    briefing = page.get("state").json()["briefing"]
    assert briefing["layout"] == "42" and briefing["sides"] == {"red": ["Ryn", "Raze"], "blue": ["Byte", "Blink"]}
    shown = page.get(briefing["map"])
    assert shown.status_code == 200 and shown.text == layout_page(scenario, play=False)
    assert (
        "Mushroom War, layout 42" in shown.text
        and f"Ryn at {next(p.spawn for p in scenario.all_players() if p.name == 'Ryn')}" in shown.text
    )
    assert "layout 42" not in layout_page(make_scenario("mushroom_war"))  # the paper's is another picture
    assert not re.search(r"""(src|href)=["']?https?:""", shown.text)  # loads nothing
    assert 'id="map"' in page.get("").text  # the lobby's frame it is shown in


def test_under_a_split_the_map_is_each_episodes_once_it_starts():
    people, page, _ = _page("split=dev")
    briefing = page.get("state").json()["briefing"]
    assert briefing["map"] is None and "split=dev" in briefing["map_note"]
    assert page.get("map").status_code == 404
    episode = make_scenario("mushroom_war").with_layout(7)
    people.show_layout(episode)  # the people's part at the episode's start (match/people_part.py)
    briefing = page.get("state").json()["briefing"]
    assert briefing["layout"] == "7" and page.get(briefing["map"]).text == layout_page(episode, play=False)


class _Seated:
    """A person's player whose run the relay stops to run a program (people/relay.py `program`)."""

    stopped = 0

    async def stop(self) -> None:
        self.stopped += 1


def test_the_signal_button_chats_the_teammates_signal_as_the_chat_box_would():
    people, page, _ = _page()
    token = page.post("join", json={"name": "alice", "player": "Ryn"}).json()["result"]["token"]
    assert page.get("state", params={"token": token}).json()["teammates"] == ["Raze"]
    player = _Seated()
    people.players, people.phase, people._queues = {"Ryn": player}, "playing", {"Ryn": []}  # type: ignore[dict-item]
    sent = page.post("signal", json={"token": token, "to": "Raze"}).json()
    assert sent == {"ok": True, "result": "[Raze signal]"}
    assert page.post("chat", json={"token": token, "text": "[Raze signal]"}).json()["ok"]
    assert people._queues["Ryn"] == ['bot.chat("[Raze signal]")'] * 2 and player.stopped == 2
    for to in ("Byte", "Ryn", None):
        refused = page.post("signal", json={"token": token, "to": to})
        assert refused.status_code == 409 and "is not a teammate of Ryn (teammates: Raze)" in refused.json()["error"]
    assert people._queues["Ryn"] == ['bot.chat("[Raze signal]")'] * 2


class _Held:
    """A person's player whose run the whistle stops (people/relay.py `end`)."""

    stops = 0

    async def stop(self) -> None:
        self.stops += 1


async def test_after_the_whistle_the_page_says_the_score_and_what_happens_next():
    people, page, _ = _page()
    people.run_dir, people.planned = "/runs/study", 2
    token = page.post("join", json={"name": "alice", "player": "Ryn"}).json()["result"]["token"]

    def seen() -> dict:
        return page.get("state", params={"token": token}).json()

    episodes = people.episodes(iter([0, 1]))
    assert next(episodes) == 0 and seen()["next"].startswith("Episode 1 (the run plans 2;")
    # the game on, as `begin` puts it, without a game
    people.players, people.phase = {"Ryn": _Held()}, "playing"  # type: ignore[dict-item]
    await people.end({"red": 3.0, "blue": 5.0})
    state = seen()
    assert state["phase"] == "over" and state["board"]["final"] == {"red": 3.0, "blue": 5.0}
    assert "being recorded" in state["next"] and people.players["Ryn"].stops == 1  # type: ignore[attr-defined]
    assert next(episodes) == 1  # decided once the episode is recorded: the next one
    assert seen()["next"].startswith("Episode 2 (the run plans 2; one spoiled on our side is played again) starts")
    assert "nothing to press" in seen()["next"] and "the whistle: red 3, blue 5 (final)" in seen()["feed"]
    assert next(episodes, None) is None  # no more: the run is over
    state = seen()
    assert state["phase"] == "done" and state["run_dir"] == "/runs/study"
    assert state["next"] == "The run is over: results in /runs/study; you can close this page."
    shown = page.get("").text  # the page shows it, and says it once its server is gone
    assert "'The whistle: ' + final + '. ' + s.next" in shown and "function gone ()" in shown
