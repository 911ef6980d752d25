"""The team API: the multi-agent system controlling one side.

A team object persists across the episodes of a series (that is how teams learn). Per episode:
`pre_game` (not timed; its duration is recorded), `play` (the game: returns when done or is
cancelled at the whistle; all of its players' code is stopped then), `post_game`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar, Protocol

from pillagerbench.llm import LLMClient
from pillagerbench.rundir import LastEpisode, TeamState
from pillagerbench.scenarios import Scenario, Side
from pillagerbench.server.clock import TICK_S, GameClock, RealClock
from pillagerbench.teams.options import TeamOptions


class PlayerHandle(Protocol):
    """A player as a team drives it in an episode (the match hands out `match/player.RecordedPlayer`s
    over the players' bots): run a program to its end, or stop it."""

    name: str

    async def run(self, code: str, *, timeout: float | None = None, on_event: Callable | None = None) -> list: ...

    async def stop(self) -> None: ...

    async def observe(self) -> list: ...


@dataclass
class TeamContext:
    """What a team gets in each phase of an episode."""

    scenario: Scenario
    side: Side
    players: dict[str, PlayerHandle]  # player name -> its handle for this episode
    episode: int
    out_dir: Path  # this team's artefacts for this episode
    observations: dict[str, list] = field(default_factory=dict)  # events from the players' reset
    episode_length: float = 120.0
    deadline: float | None = None  # the clock's now() at the whistle (set when the game starts)
    last_episode: LastEpisode = field(default_factory=lambda: LastEpisode())  # what the team saw of its last episode
    seed: int = 0
    llm: LLMClient | None = None  # an LLM client for LLM teams
    # the LLM teams' loop (config `protocol`): "pillagerbench" (ours: reruns, re-asks) or "upstream"
    # (the paper's: no rerun after the iteration cap or a failed answer, CoT's 10 steps, no re-asks)
    protocol: str = "pillagerbench"
    # game time (config `clock`; server/clock.py): the wall clock, or the arena's lockstep ticks
    clock: GameClock = field(default_factory=RealClock)
    # the scoreboard: each side's score at the last whole second of the game (the match's sample)
    scores: dict[str, float] = field(default_factory=dict)
    # the side's players people play (from the page or a Minecraft client: docs/people.md): their handles are seats the team
    # cannot drive, and what they say in chat is for the team's agents to hear (teams/heard.py)
    people: tuple[str, ...] = ()

    @property
    def upstream_protocol(self) -> bool:
        return self.protocol == "upstream"

    def time_left(self) -> float:
        """Seconds of game time to the whistle."""
        return float("inf") if self.deadline is None else max(0.0, self.deadline - self.clock.now())

    def wall_limit(self) -> float | None:
        """How long an LLM call may take on the wall clock: to the whistle on the real clock; on the
        lockstep clock the world waits for the answer (None)."""
        return self.time_left() if self.clock.mode == "real" else None

    async def sleep(self, seconds: float, player: str | None = None) -> None:
        """Wait `seconds` of game time, or to the whistle if that comes first. `player`: the player
        whose loop waits (on the lockstep clock its bot, idle since its last run, holds the world until
        its team says what next: this is what next). A player's wait that reaches the whistle ends its
        game: it holds the world no more (with scoring=upstream the game plays on past the whistle, and
        it held the world there until the server let go of it; a run begun after is not waited for)."""
        wait = min(seconds, self.time_left())
        if player is None:
            await self.clock.sleep(wait)
            return
        await self.clock.rest([player], wait)
        if self.time_left() < 1e-6:  # (game seconds are ticks x 0.05: not exact in floating point)
            await self.clock.retire([player])

    async def pause_before_rerun(self, player: str, pause_s: float, started: float, failed: bool) -> None:
        """A team's loop that restarts a player's program waits `pause_s` of game time since the run
        `started` (none once it ran that long); a run that could not start (a bot dead for good) waits a
        tick at least, whatever `pause_s`: a loop that restarts never spins without yielding."""
        pause = max(pause_s - (self.clock.now() - started), TICK_S if failed else 0.0)
        if self.time_left() > 0 and pause > 0:
            await self.sleep(pause, player)

    @property
    def opponent(self) -> Side:
        return self.scenario.opponent(self.side.key)


class Team:
    """Base class. `name` is the config name; `scenarios` the scenario keys it can play (None = all)."""

    name: ClassVar[str] = "team"
    scenarios: ClassVar[tuple[str, ...] | None] = None
    uses_llm: ClassVar[bool] = False  # the match gives it an LLM client (ctx.llm) from the `llm` config
    # the options `red.KEY=VALUE` may set: types, ranges, defaults, descriptions (teams/options.py);
    # conf/team/<name>.yaml repeats them for a built-in team (tests/teams/test_options.py)
    Options: ClassVar[type[TeamOptions]] = TeamOptions
    # or, shorter, for a team of your own: the options with their defaults (their types are the defaults')
    options_declared: ClassVar[dict[str, Any]] = {}

    def __init__(self, **options: object):
        self.options = options
        self.iterations: list[int] = []  # code iterations per player per episode (the paper's I)
        self.problems: list[str] = []  # what went wrong this episode (the match records it)

    @classmethod
    def check_options(cls, options: dict[str, Any]) -> list[str]:
        """Problems with these options, one line each, found before anything starts."""
        return []

    @classmethod
    async def preflight(cls, options: dict[str, Any]) -> str | None:
        """One cheap check that the team can play (e.g. its server answers), before episode 0."""
        return None

    async def pre_game(self, ctx: TeamContext) -> None:
        """Plan before the clock starts."""

    async def play(self, ctx: TeamContext) -> None:
        """Drive the players until the whistle (the match cancels this task then)."""
        await ctx.clock.rest(list(ctx.side.player_names), ctx.time_left())  # lockstep: its idle bots let the world go

    async def post_game(self, ctx: TeamContext) -> None:
        """Look back after the game (ctx.last_episode holds this episode's record)."""

    def state(self) -> dict[str, Any]:
        """What a checkpoint keeps (JSON-serialisable)."""
        return {}

    def load_state(self, state: dict[str, Any]) -> None:
        pass

    def save_checkpoint(self, directory: Path) -> Path:
        return TeamState(self.name, self.state()).write(directory)

    def load_checkpoint(self, directory: Path) -> None:
        saved = TeamState.read(directory)
        if saved.team != self.name:
            raise ValueError(f"checkpoint {directory} is of team {saved.team!r}, not {self.name!r}")
        self.load_state(saved.state)
