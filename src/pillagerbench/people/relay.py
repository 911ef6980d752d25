"""The relay from people's pages to their players (docs/people.md). Each person's player is the same
mineflayer bot an agent's is (players/); while the game is on it runs the person's run, which waits, and
the page's keys and mouse are done inside it (the bot's `act` op, js/bot/person.js), so the server's checks
and the gate that drops what outlives a run hold for people as for agents. A primitive button or a chat
line is a program run like an agent's (the same primitives, the same sandbox), after which the person's
run goes on. A page gone quiet (closed, connection lost) leaves its player standing still."""

from __future__ import annotations

import asyncio
import functools
import json
import re
import time
from collections.abc import Callable, Iterable, Iterator
from typing import Any

from pillagerbench.people.lobby import layout_page
from pillagerbench.people.seats import Refused, Seats
from pillagerbench.players import Player, PlayerError
from pillagerbench.scenarios import Scenario

HOLD = "await new Promise(() => {})"  # the person's run: it waits, and the person's input acts inside it
FEED = 200  # lines of the events feed a page is shown
STILL = {"what": "controls", "controls": {}}
HUD_S = 0.3  # how often a person's page is given its player's hud (hotbar, inventory, health, food, look)
SIGNAL = re.compile(r"\[(\w+) signal\]|\[waiting signal\]|\[signal (recieved|timeout)\]")  # multiAgent.js


def whistle_line(final: dict[str, float]) -> str:
    """What people are told at the whistle: `the whistle: red 3, blue 5`."""
    return "the whistle: " + ", ".join(f"{k} {v:g}" for k, v in final.items())


class People:
    """The people of one match: their seats, their feed, and their players while a game is on."""

    def __init__(self, seats: dict[str, list[str]], briefing: dict[str, Any]):
        self.seats = Seats(seats)
        self.briefing = briefing  # what the lobby shows: scenario, description, sides, map (lobby.briefing_of)
        self.map_page = ""  # the map of the layout played (lobby.layout_page), served at the briefing's `map`
        self.players: dict[str, Player] = {}
        self.sink: Callable[[str, list], None] | None = None
        self.phase = "lobby"  # lobby | waiting | playing | over (an episode's whistle) | done (the run is over)
        self.next = ""  # what happens next, shown from the whistle on (`end`, `episodes`, `done`)
        self.run_dir = ""  # where the run's results are (match/run.py)
        self.planned = 0  # the episodes the run plans (a spoiled one is played again: config `retries`)
        self.feed: list[str] = []
        self.board: dict[str, Any] = {}  # scores, clock
        self.huds: dict[str, dict[str, Any]] = {}  # player -> what its page shows of it (the bot's hud op)
        self.chats: dict[str, list[dict[str, Any]]] = {}  # player -> the server's chat its bot heard
        self.views: dict[str, dict[str, Any]] = {}  # player -> its first-person view: {port} or {error}
        self.end_at = 0.0
        self._queues: dict[str, list[str]] = {}
        self._loops: list[asyncio.Task] = []
        self._ready = asyncio.Event()

    def say(self, line: str) -> None:
        self.feed = [*self.feed, line][-FEED:]

    # ---- the lobby ----------------------------------------------------------------------------
    def show_layout(self, scenario: Scenario) -> None:
        """The pages show the map of `scenario`'s layout (the one played: before the first episode, or each
        episode's when `split=` gives each its own)."""
        key = str(scenario.layout_key)
        if self.map_page and self.briefing.get("layout") == key:
            return
        self.map_page = layout_page(scenario, play=False)
        version = int(self.briefing.get("map_version") or 0) + 1
        self.briefing = {**self.briefing, "layout": key, "map": f"map?v={version}", "map_version": version}

    def ready(self, token: str | None) -> None:
        seat = self.seats.of(token)
        seat.ready = True
        self.say(f"{seat.person} ({seat.player}) is ready")
        if self.seats.all_ready():
            self._ready.set()

    async def wait_ready(self, timeout: float) -> bool:
        """Whether every person was ready within `timeout` seconds."""
        self.phase = "waiting"
        try:
            await asyncio.wait_for(self._ready.wait(), timeout)
        except asyncio.TimeoutError:
            return False
        return True

    # ---- the game -----------------------------------------------------------------------------
    def begin(self, players: dict[str, Player], sink: Callable[[str, list], None], length: float) -> None:
        """The game is on: each person's player runs the person's run until `length` seconds from now."""
        self.players = {name: players[name] for name in self.seats.seats}
        self.sink, self.phase, self.end_at = sink, "playing", time.monotonic() + length
        self.next = ""
        self._queues = {name: [] for name in self.players}
        self.huds, self.chats = {}, {name: [] for name in self.players}
        self.say("the game is on")
        self._loops = [asyncio.create_task(self._hold(name)) for name in self.players]
        self._loops += [asyncio.create_task(self._watch(name)) for name in self.players]
        self._loops += [asyncio.create_task(self._view(name)) for name in self.players if name not in self.views]

    async def end(self, final: dict[str, float] | None = None) -> None:
        """The whistle: the person's runs end (the match stops every player), the pages are told the final
        score; what follows is told once the episode is recorded (`episodes`)."""
        self.phase, self.end_at = "over", 0.0
        # the person's run the hold loop started after the whistle's stop is stopped too (its loop ends with it):
        # a run left going would outlive the episode and the next whistle's stop would wait for it in vain
        await asyncio.gather(*(player.stop() for player in self.players.values()), return_exceptions=True)
        for task in self._loops:
            task.cancel()
        await asyncio.gather(*self._loops, return_exceptions=True)
        self._loops = []
        self.next = "The episode is over; it is being recorded, and what follows is told here in a moment."
        if final is not None:
            self.board = {**self.board, "final": final}
            self.say(whistle_line(final) + " (final)")

    def episodes(self, indices: Iterable[int]) -> Iterator[int]:
        """The match's episode indices, each told to the pages as it is decided (after the last one was
        recorded: rundir/schedule.py), and at the end that the run is over."""
        for index in indices:
            self.next = (
                f"Episode {index + 1} (the run plans {self.planned}; one spoiled on our side is played again) starts "
                "as soon as the arena is reset and every team's pre-game is done (a few seconds; an LLM team's takes "
                "longer): nothing to press, stay on this page."
            )
            self.say(f"next: episode {index + 1}")
            yield index
        self.done()

    def done(self) -> None:
        """The run is over: the pages say where its results are and that they may be closed."""
        self.phase = "done"
        self.next = f"The run is over: results in {self.run_dir or 'the run directory'}; you can close this page."
        self.say("the run is over")

    async def _hold(self, name: str) -> None:
        player = self.players[name]
        while self.phase == "playing" and time.monotonic() < self.end_at:
            queue = self._queues[name]
            code = queue.pop(0) if queue else HOLD
            try:
                events = await player.run(code, on_event=functools.partial(self._heard, name))
            except PlayerError as exc:
                self.say(f"{name}: {exc}")
                await asyncio.sleep(0.5)
                continue
            for event in events:
                if self.sink is not None:
                    self.sink(name, event)
                if event and event[0] == "onError" and code != HOLD:
                    self.say(f"{name}: refused: {str((event[1] or {}).get('onError', ''))[:300]}")
            if code != HOLD:
                self.say(f"{name}: done: {code[:120]}")

    def _heard(self, name: str, event: list) -> None:
        """A chat line the player's bot heard (the server's chat: players, teammates' signals, the game's
        messages), as it happens."""
        if len(event) < 2 or event[0] != "onChat":
            return
        text = str((event[1] or {}).get("onChat", ""))[:300]
        self.chats[name] = [*self.chats.get(name, []), {"text": text, "signal": bool(SIGNAL.search(text))}][-FEED:]

    async def _watch(self, name: str) -> None:
        """The player's hud for its page, every HUD_S seconds while the game is on."""
        player = self.players[name]
        while self.phase == "playing":
            try:
                self.huds[name] = await player.channel.hud()
            except PlayerError:
                pass
            await asyncio.sleep(HUD_S)

    async def _view(self, name: str) -> None:
        """The player's bot starts its first-person view (js/bot/view.js) on a loopback port; without the
        optional prismarine-viewer the page is told why there is none."""
        try:
            self.views[name] = {"port": await self.players[name].channel.view()}
        except PlayerError as exc:
            self.views[name] = {"error": str(exc).splitlines()[0]}

    def _player(self, token: str | None) -> tuple[str, Player]:
        seat = self.seats.of(token)
        if self.phase != "playing" or seat.player not in self.players:
            raise Refused("the game is not on: nothing you do acts now")
        return seat.player, self.players[seat.player]

    async def act(self, token: str | None, what: dict[str, Any]) -> str:
        """A key or mouse input of the page whose seat `token` holds; Refused with the game's reason."""
        name, player = self._player(token)
        try:
            return await player.channel.act(what)
        except PlayerError as exc:
            raise Refused(str(exc).splitlines()[0]) from None

    async def program(self, token: str | None, code: str) -> None:
        """A primitive button or a chat line: run as an agent's program would be, then the person's run again."""
        name, player = self._player(token)
        self._queues[name].append(code)
        await player.stop()  # ends the person's waiting run; the hold loop runs the code next

    def teammates(self, player: str) -> list[str]:
        """The other players of `player`'s side (the briefing's `sides`): whom its person may signal."""
        for names in (self.briefing.get("sides") or {}).values():
            if player in names:
                return [n for n in names if n != player]
        return []

    async def signal(self, token: str | None, to: object) -> str:
        """The person's signal to the teammate `to`: the chat line `[TO signal]` that multiAgent.js's sendSignal
        chats and a teammate's waitSignal waits for, sent as the chat box sends a line; the line sent."""
        seat = self.seats.of(token)
        mates = self.teammates(seat.player)
        if to not in mates:
            raise Refused(f"{to!r} is not a teammate of {seat.player} (teammates: {', '.join(mates) or 'none'})")
        line = f"[{to} signal]"
        await self.program(token, chat_code(line))
        return line

    async def still(self) -> None:
        """Players whose page has gone quiet stand still."""
        for seat in self.seats.seats.values():
            if not seat.connected and seat.player in self.players and self.phase == "playing":
                try:
                    await self.players[seat.player].channel.act(STILL)
                except PlayerError:
                    pass

    def state(self, token: str | None) -> dict[str, Any]:
        seat = None
        try:
            seat = self.seats.of(token) if token else None
        except Refused:
            seat = None
        left = max(0.0, self.end_at - time.monotonic()) if self.phase == "playing" else None
        return {
            "phase": self.phase,
            "seat": seat.view() if seat else None,
            "seats": [s.view() for s in self.seats.seats.values()],
            "briefing": self.briefing,
            "board": {**self.board, "left": left},
            "next": self.next,
            "run_dir": self.run_dir,
            "feed": self.feed[-40:],
            "hud": self.huds.get(seat.player) if seat else None,
            "chat": self.chats.get(seat.player, [])[-40:] if seat else [],
            "teammates": self.teammates(seat.player) if seat else [],
            "view": self.views.get(seat.player) if seat else None,
        }


class SeatHandle:
    """The handle a team gets for a player a person plays: the team cannot drive it (a run waits for the
    whistle, which cancels it), so a mixed team's agent plays only its own players."""

    def __init__(self, name: str, observe: Callable[[], Any]):
        self.name, self._observe = name, observe

    async def run(self, code: str, *, timeout: float | None = None, on_event: Callable | None = None) -> list:
        await asyncio.Event().wait()
        return []

    async def stop(self) -> None:
        return None

    async def observe(self) -> list:
        return await self._observe()


def code_of(primitive: str, args: list[Any]) -> str:
    """The program a primitive button runs: the same call an agent's code makes."""
    return f"await {primitive}(bot, {', '.join(json.dumps(a) for a in args)})"


def chat_code(text: str) -> str:
    """The program a chat line runs (the chat box, the signal button): the bot says `text`; nothing for ''."""
    return f"bot.chat({json.dumps(text)})" if text else ""
