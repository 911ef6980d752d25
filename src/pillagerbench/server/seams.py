"""The seams to the arena server, as the game master, the players and the match see it: small
Protocols, so that each side names what it uses (the arena's `ArenaServer` is the one real
implementation; `server/process.py`).

The control channel's ops are declared once, in `js/server/control_ops.json` (each op's arguments with
their types, and its answer's type), which `js/server/control.js` dispatches from. `Control` has one
typed method per op, named as the op, each argument named as on the wire (`from_` for `from`);
`tests/server/test_control_ops.py` checks both sides against the declaration.
"""

from __future__ import annotations

import asyncio
import json
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any, NamedTuple, Protocol, TypedDict

from pillagerbench.host.node import JS_DIR

DECLARATION = JS_DIR / "server" / "control_ops.json"

Pos = Sequence[float]  # [x, y, z]; a block position is floored by the server
Stack = Sequence[Any] | Mapping[str, Any]  # [item name, count] or {"name", "count"}


class BlockState(TypedDict):
    name: str
    properties: dict[str, Any]
    state: int


class PlayerInfo(TypedDict):
    name: str
    pos: list[float]
    health: float
    gamemode: int


class Slot(TypedDict):
    slot: int
    name: str
    count: int


class Given(TypedDict):
    given: int
    left: int


class Furnace(TypedDict):
    input: list[Any] | None  # [item name, count]
    fuel: list[Any] | None
    output: list[Any] | None
    burning: bool
    progress: float


class Status(TypedDict):
    players: list[str]
    tps: float
    tick: int
    entities: int


class MobInfo(TypedDict):
    id: int
    name: str
    pos: list[float]
    health: float


class ItemEntity(TypedDict):
    id: int
    item: str
    count: int
    pos: list[float]
    thrower: str | None


class ReplayFrame(TypedDict):
    tick: int
    players: list[list[Any]]
    items: list[list[Any]]
    mobs: list[list[Any]]
    blocks: list[list[Any]]


class ClockState(TypedDict):
    mode: str  # "real" or "lockstep"
    tick: int
    speed: float | None  # a multiple of real time; None: unpaced
    holds: list[str]
    bots: int
    let_go: dict[str, int]  # idle:NAME -> times the server let go of it in the last game (lockstep)


class OpSpec(NamedTuple):
    """One declared op: its arguments (wire name -> type; optional ones may be left out) and answer."""

    name: str
    args: dict[str, str]
    optional: frozenset[str]
    result: str
    doc: str
    waits: bool = False  # answers when something happens (no reply timeout)


def read_declaration(path: Path = DECLARATION) -> tuple[dict[str, OpSpec], dict[str, dict[str, str]]]:
    """The declared ops (in their declared order) and the types they use, from `control_ops.json`."""
    data = json.loads(path.read_text(encoding="utf-8"))
    ops = {}
    for name, spec in data["ops"].items():
        args = {a: t.removesuffix("?") for a, t in spec["args"].items()}
        optional = frozenset(a for a, t in spec["args"].items() if t.endswith("?"))
        ops[name] = OpSpec(name, args, optional, spec["result"], spec["doc"], spec.get("waits", False))
    return ops, data["types"]


OPS, TYPES = read_declaration()


class UndeclaredOp(TypeError):
    """A typed method sent an op or an argument the declaration does not have (a bug on our side)."""


class Control(Protocol):
    """The control channel: one request, one answer (game masters, arenas, players' server checks).

    Implementations give `request`; the typed ops below send through it. What each op does is in
    `control_ops.json` (and each method's `__doc__`)."""

    async def request(self, op: str, **args: Any) -> Any: ...

    async def send(self, op: str, **args: Any) -> Any:
        """Send declared op `op` with the arguments that are not None (those are left out)."""
        spec = OPS.get(op)
        if spec is None or not args.keys() <= spec.args.keys():
            raise UndeclaredOp(f"{op}({', '.join(args)}) is not declared in {DECLARATION.name}")
        sent = {k: v for k, v in args.items() if v is not None}
        return await (self.request(op, timeout=None, **sent) if spec.waits else self.request(op, **sent))

    async def ping(self) -> str:
        return await self.send("ping")

    async def status(self) -> Status:
        return await self.send("status")

    async def get_block(self, pos: Pos) -> BlockState:
        return await self.send("get_block", pos=pos)

    async def set_block(self, pos: Pos, block: str, properties: Mapping[str, Any] | None = None) -> bool:
        return await self.send("set_block", pos=pos, block=block, properties=properties)

    async def set_blocks(self, blocks: Sequence[Sequence[Any]]) -> int:
        return await self.send("set_blocks", blocks=blocks)

    async def fill(self, from_: Pos, to: Pos, block: str, properties: Mapping[str, Any] | None = None) -> int:
        return await self.send("fill", **{"from": from_}, to=to, block=block, properties=properties)

    async def scan(self, from_: Pos, to: Pos) -> list[list[Any]]:
        return await self.send("scan", **{"from": from_}, to=to)

    async def find_blocks(self, names: Sequence[str], center: Pos, radius: float) -> list[list[Any]]:
        return await self.send("find_blocks", names=names, center=center, radius=radius)

    async def players(self) -> list[PlayerInfo]:
        return await self.send("players")

    async def inventory(self, player: str) -> list[Slot]:
        return await self.send("inventory", player=player)

    async def give(self, player: str, item: str, count: int | None = None) -> Given:
        return await self.send("give", player=player, item=item, count=count)

    async def take(self, player: str, item: str, count: int | None = None) -> int:
        return await self.send("take", player=player, item=item, count=count)

    async def clear(self, player: str) -> bool:
        return await self.send("clear", player=player)

    async def set_inventory(self, player: str, items: Mapping[str, int] | None = None) -> list[Slot]:
        return await self.send("set_inventory", player=player, items=items)

    async def teleport(self, player: str, pos: Pos, yaw: float | None = None, pitch: float | None = None) -> bool:
        return await self.send("teleport", player=player, pos=pos, yaw=yaw, pitch=pitch)

    async def gamemode(self, player: str, mode: str) -> bool:
        return await self.send("gamemode", player=player, mode=mode)

    async def chat(self, message: str) -> bool:
        return await self.send("chat", message=message)

    async def tell(self, player: str, message: str) -> bool:
        return await self.send("tell", player=player, message=message)

    async def tick_rate(self, tps: float) -> bool:
        return await self.send("tick_rate", tps=tps)

    async def crop_growth(self, chance: float | None = None, random_tick_speed: int | None = None) -> bool:
        return await self.send("crop_growth", chance=chance, random_tick_speed=random_tick_speed)

    async def crop_growth_speed(self, pos: Pos) -> float:
        return await self.send("crop_growth_speed", pos=pos)

    async def summon(self, mob: str, pos: Pos) -> int:
        return await self.send("summon", mob=mob, pos=pos)

    async def mobs(self) -> list[MobInfo]:
        return await self.send("mobs")

    async def items(self) -> list[ItemEntity]:
        return await self.send("items")

    async def spawn_item(self, item: str, pos: Pos, count: int | None = None, delay_ticks: int | None = None) -> int:
        return await self.send("spawn_item", item=item, count=count, pos=pos, delay_ticks=delay_ticks)

    async def remove_entities(self) -> bool:
        return await self.send("remove_entities")

    async def set_chest(self, pos: Pos, items: Mapping[str, int]) -> Mapping[str, int]:
        return await self.send("set_chest", pos=pos, items=items)

    async def get_chest(self, pos: Pos) -> Mapping[str, int]:
        return await self.send("get_chest", pos=pos)

    async def set_furnace(
        self, pos: Pos, input: Stack | None = None, fuel: Stack | None = None, output: Stack | None = None
    ) -> Furnace:
        return await self.send("set_furnace", pos=pos, input=input, fuel=fuel, output=output)

    async def get_furnace(self, pos: Pos) -> Furnace:
        return await self.send("get_furnace", pos=pos)

    async def egg_farm(self, chest: Pos, interval_s: float, radius: float | None = None) -> bool:
        return await self.send("egg_farm", chest=chest, interval_s=interval_s, radius=radius)

    async def reset_state(self) -> bool:
        return await self.send("reset_state")

    async def replay_frame(self, start: bool | None = None, stop: bool | None = None) -> ReplayFrame:
        return await self.send("replay_frame", start=start, stop=stop)

    async def watch(
        self,
        center: Pos | None = None,
        title: str | None = None,
        episode: int | None = None,
        t: float | None = None,
        length: float | None = None,
        scores: Mapping[str, float] | None = None,
        sides: Mapping[str, str] | None = None,
    ) -> bool:
        return await self.send(
            "watch", center=center, title=title, episode=episode, t=t, length=length, scores=scores, sides=sides
        )

    async def clock(
        self,
        speed: float | None = None,
        unpaced: bool | None = None,
        drop_holds: bool | None = None,
        game: bool | None = None,
    ) -> ClockState:
        return await self.send("clock", speed=speed, unpaced=unpaced, drop_holds=drop_holds, game=game)

    async def hold(self, who: str) -> int:
        return await self.send("hold", who=who)

    async def release(self, who: str) -> int:
        return await self.send("release", who=who)

    async def wait_tick(self, tick: int, hold: str | None = None, release: str | None = None) -> int:
        return await self.send("wait_tick", tick=tick, hold=hold, release=release)

    async def rest(self, players: Sequence[str], ticks: int) -> int:
        return await self.send("rest", players=players, ticks=ticks)

    async def retire(self, players: Sequence[str]) -> int:
        return await self.send("retire", players=players)

    async def free(self, players: Sequence[str]) -> int:
        return await self.send("free", players=players)

    async def seed(self, seed: int) -> bool:
        return await self.send("seed", seed=seed)

    async def player_order(self, names: Sequence[str]) -> list[str]:
        return await self.send("player_order", names=names)


for _op in OPS.values():  # each typed method's documentation is its op's, from the declaration
    if (_method := getattr(Control, _op.name, None)) is not None:
        _method.__doc__ = _op.doc


class Events(Protocol):
    """What the server pushes (chat, refusals, ...): a queue per subscriber."""

    def subscribe(self) -> asyncio.Queue: ...

    def unsubscribe(self, q: asyncio.Queue) -> None: ...


class Server(Control, Protocol):
    """A running arena server as a match uses it."""

    port: int | None
    watch_url: str | None

    @property
    def control(self) -> Events | None: ...

    @property
    def alive(self) -> bool: ...

    async def start(self) -> Any: ...

    async def stop(self) -> None: ...
