"""The bot's stdio protocol as Python sees it, declared once in `js/bot/bot_protocol.json` (which
`js/bot/main.js` dispatches from, through `js/bot/protocol.js`): the declared ops (`OPS`, read as the
control channel's are, `server.seams.read_declaration`), `BotOps` (one typed method per op, named as the
op, each argument named as on the wire; every line sent is checked against the declaration first), the
settings a bot is started with (`Settings`) and the answers' shapes. The observation's fields are typed
in `observation.py`. `tests/players/test_bot_protocol.py` checks all of them against the declaration,
and the JavaScript too.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any, NamedTuple, TypedDict

from pillagerbench.host.node import JS_DIR
from pillagerbench.server.seams import OpSpec, UndeclaredOp, read_declaration

from .observation import Observation, Position

DECLARATION = JS_DIR / "bot" / "bot_protocol.json"

Equipment = Sequence[str | None] | dict[str, Any]  # six names (head .. off hand) or {destination: name}


class Declaration(NamedTuple):
    """The declaration read: ops, how each is answered, types, and the fields of the settings, the lines
    out and the observation (name -> type; '?': optional)."""

    ops: dict[str, OpSpec]
    answers: dict[str, str]  # op -> reply, run or spawned
    types: dict[str, dict[str, str]]
    settings: dict[str, str]
    lines: dict[str, Any]  # line kind -> an example of its value
    observation: dict[str, str]
    status: dict[str, str]


def read_protocol(path: Path = DECLARATION) -> Declaration:
    """The bot's protocol, from `bot_protocol.json` (ops in their declared order)."""
    data = json.loads(path.read_text(encoding="utf-8"))
    ops, types = read_declaration(path)
    return Declaration(
        ops=ops,
        answers={op: spec.get("answer", "reply") for op, spec in data["ops"].items()},
        types=types,
        settings={name: s["type"] for name, s in data["settings"].items()},
        lines={kind: line["example"] for kind, line in data["lines"].items()},
        observation=data["observation"],
        status=data["status"],
    )


PROTOCOL = read_protocol()
OPS = PROTOCOL.ops
# Ops Python sends without waiting here for their answer: login (the spawned line answers it), run (its
# answer ends the run: Player._dispatch) and stop (the run's end answers it).
POSTED = frozenset({"login", "run", "stop"})


class _RequiredSettings(TypedDict):
    port: int
    username: str


class Settings(_RequiredSettings, total=False):
    """The one JSON argument a bot process is started with (`settings` in the declaration: an optional
    one may be left out, or None)."""

    host: str | None
    primitives: Sequence[str] | None
    clock: str | None
    heartbeatMs: int | None
    cue: bool | None
    view: bool | None


class Permissions(TypedDict):
    enabled: bool
    fsWrite: bool
    fsReadRoot: bool
    childProcess: bool
    worker: bool
    addons: bool


class LagReport(TypedDict):
    ticks: int
    wall_s: float
    tick_rate: float | None
    late_mean_ms: float
    late_max_ms: float
    late_pct: float


class RunEnd(TypedDict):
    stopped: bool
    tick: int | None


class Spawned(TypedDict):
    username: str
    position: Position


def request_line(op: str, args: Mapping[str, object], rid: int | None, ops: Mapping[str, OpSpec] = OPS) -> dict:
    """The line of declared op `op` with the arguments that are not None (those are left out), with id
    `rid` unless None; an undeclared op or argument, or a required one missing, is refused (our bug)."""
    spec = ops.get(op)
    sent = {k: v for k, v in args.items() if v is not None}
    if spec is None or not args.keys() <= spec.args.keys() or not spec.args.keys() - spec.optional <= sent.keys():
        raise UndeclaredOp(f"{op}({', '.join(args)}) is not declared in {DECLARATION.name}")
    return ({} if rid is None else {"id": rid}) | {"op": op} | sent


class BotOps:
    """The bot's ops as typed methods. Implementations give `next_id`, `send` (one line) and `_exchange`
    (send a line, wait up to `wait` seconds for its reply's result); what each op does is in
    `bot_protocol.json` (and each method's `__doc__`)."""

    def next_id(self) -> int:
        raise NotImplementedError

    async def send(self, msg: dict) -> None:
        raise NotImplementedError

    async def _exchange(self, rid: int, line: dict, wait: float) -> Any:
        raise NotImplementedError

    async def _ask(self, op: str, wait: float = 10.0, **args: object) -> Any:
        rid = self.next_id()
        return await self._exchange(rid, request_line(op, args, rid), wait)

    async def login(self) -> None:
        await self.send(request_line("login", {}, None))

    async def ping(self) -> str:
        return await self._ask("ping")

    async def permissions(self) -> Permissions:
        return await self._ask("permissions")

    async def memory(self, gc: bool | None = None) -> dict[str, float]:
        return await self._ask("memory", gc=gc)

    async def run(self, code: str, timeout: float | None = None, *, rid: int) -> None:
        await self.send(request_line("run", {"code": code, "timeout": timeout}, rid))

    async def stop(self) -> None:
        await self.send(request_line("stop", {}, self.next_id()))

    async def observe(self) -> Observation:
        return await self._ask("observe")

    async def lag(self, reset: bool | None = None) -> LagReport:
        return await self._ask("lag", reset=reset)

    async def clear(self, seed: int | None = None) -> bool:
        return await self._ask("clear", seed=seed)

    async def equip(self, equipment: Equipment, *, wait: float = 15.0) -> bool:
        return await self._ask("equip", wait, equipment=equipment)

    async def act(self, input: dict[str, Any], *, wait: float = 10.0) -> str:
        return await self._ask("act", wait, input=input)

    async def hud(self) -> dict[str, Any]:
        return await self._ask("hud")

    async def view(self, *, wait: float = 20.0) -> int:
        return await self._ask("view", wait)

    async def settle(
        self, pos: Sequence[float] | None = None, timeout: float | None = None, *, wait: float = 10.0
    ) -> bool | Position:
        return await self._ask("settle", wait, pos=pos, timeout=timeout)


for _op in OPS.values():  # each typed method's documentation is its op's, from the declaration
    if (_method := getattr(BotOps, _op.name, None)) is not None:
        _method.__doc__ = _op.doc
