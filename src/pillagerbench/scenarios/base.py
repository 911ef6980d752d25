"""What every scenario provides: sides and players, the arena, the description for LLMs, the
primitives it allows, and its game master (the rules that run during the game)."""

from __future__ import annotations

import random
from abc import ABC, abstractmethod
from dataclasses import dataclass, field, replace
from typing import Any, ClassVar, Generic

from pillagerbench.scenarios.arena import Arena
from pillagerbench.scenarios.layout import LayoutKey, LayoutRules, LayoutT, split_of
from pillagerbench.server.seams import Control


@dataclass(frozen=True)
class PlayerSpec:
    name: str
    spawn: tuple[float, float, float]  # block coordinates; players stand at the block's centre
    gamemode: str = "survival"  # Dash & Dine's servers are creative (unkillable), as upstream's


@dataclass(frozen=True)
class Side:
    key: str  # "red" or "blue"
    team_name: str  # "red_team"
    color: str
    players: tuple[PlayerSpec, ...]
    center: tuple[float, float, float]

    @property
    def player_names(self) -> list[str]:
        return [p.name for p in self.players]


class GameMaster(ABC):
    """The scenario's rules during the game. It talks to the world only through the control
    channel (`server`: the typed ops of `Control`), so a faster twin of the world can stand in for the server."""

    period_s: ClassVar[float] = 1.0

    def __init__(self, scenario: Scenario, server: Control, rng: random.Random):
        self.scenario, self.server, self.rng = scenario, server, rng
        self.log: list[dict] = []  # what the game master did, for the episode record

    async def start(self) -> None:  # noqa: B027 - a hook with nothing to do by default
        """Called once when the clock starts."""

    @abstractmethod
    async def step(self) -> None:
        """One iteration of the rules (every `period_s` seconds, and once more at the whistle)."""

    @abstractmethod
    async def scores(self) -> dict[str, float]:
        """The current score of each side, by side key."""

    async def upstream_scores(self, runs: dict[str, int]) -> dict[str, float]:
        """The score as upstream's code computed it (scoring=upstream, docs/fidelity.md), given the
        code runs each player has started so far this episode. Without quirks: `scores`."""
        return await self.scores()

    async def say(self, message: str) -> None:
        self.log.append({"chat": message})
        await self.server.chat(message)


@dataclass
class Scenario(ABC, Generic[LayoutT]):
    """A scenario instance. Subclasses set the class attributes and implement the methods."""

    key: ClassVar[str]
    title: ClassVar[str]
    primitives: ClassVar[tuple[str, ...]]
    version: ClassVar[str] = "1"
    # 0: crops grow by vanilla's random ticks at `random_tick_speed`; > 0: a fixed chance per crop per second
    crop_growth_chance: float = 0.0
    random_tick_speed: ClassVar[int] = 0  # vanilla's gamerule randomTickSpeed in the reference's world
    layouts: ClassVar[LayoutRules]  # the scenario's layouts (docs/layouts.md)
    options: dict[str, Any] = field(default_factory=dict)
    # where everything is (the scenario's layout model); None (the constructor's default): the paper's
    layout: LayoutT = None  # type: ignore[assignment]

    def __post_init__(self) -> None:
        if self.layout is None:
            self.layout = self.layouts.paper

    def with_layout(self, key: LayoutKey) -> Scenario[LayoutT]:
        """The same scenario on another layout ("paper", a seed, or a layout file)."""
        return replace(self, layout=self.layouts.make(key))

    @property
    def layout_key(self) -> LayoutKey:
        return self.layout.key

    @property
    def split(self) -> str:
        return split_of(self.layout.key)

    @property
    @abstractmethod
    def sides(self) -> tuple[Side, ...]: ...

    @property
    @abstractmethod
    def arena(self) -> Arena: ...

    @property
    def extra_players(self) -> tuple[PlayerSpec, ...]:
        """Players that belong to the scenario, not to a team (Dash & Dine's servers)."""
        return ()

    @abstractmethod
    def description(self) -> str:
        """The briefing given to LLM teams, generated from the scenario's data."""

    @abstractmethod
    def game_master(self, server, rng: random.Random) -> GameMaster: ...

    def side(self, key: str) -> Side:
        for s in self.sides:
            if s.key == key:
                return s
        raise KeyError(f"no side {key!r} in {self.title} (sides: {[s.key for s in self.sides]})")

    def opponent(self, key: str) -> Side:
        return next(s for s in self.sides if s.key != key)

    def placeholders(self, key: str) -> dict[str, Any]:
        """Values substituted into the built-in opponents' scripts ($team_name, ...)."""
        own, other = self.side(key), self.opponent(key)
        return {
            "team_name": own.team_name,
            "opponent_name": other.team_name,
            "team_center": vec(own.center),
            "opponent_center": vec(other.center),
        }

    def all_players(self) -> list[PlayerSpec]:
        return [p for s in self.sides for p in s.players] + list(self.extra_players)


PLAYER_NAMES = {"red": ("Ryn", "Raze"), "blue": ("Byte", "Blink")}  # both scenarios', as upstream's


def sides_at(spawns: dict[str, list], centers: dict[str, tuple]) -> tuple[Side, ...]:
    """Red and blue, their players (PLAYER_NAMES) at the given spawns, and their centres."""
    return tuple(
        Side(key, f"{key}_team", key, tuple(PlayerSpec(n, p) for n, p in zip(names, spawns[key])), centers[key])
        for key, names in PLAYER_NAMES.items()
    )


def vec(p) -> str:
    """A position as the argument list of `new Vec3(...)` in a script."""
    return ", ".join(_num(v) for v in p)


def _num(v: float) -> str:
    return str(int(v)) if float(v).is_integer() else str(v)
