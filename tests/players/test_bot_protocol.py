"""The bot's stdio protocol is declared once (js/bot/bot_protocol.json) and both sides agree with it: the
bot starts only when its handlers are the declared ops (answered as declared) and its settings the
declared ones (Node is asked here), and Python's typed view is the declaration's: `BotOps`' typed methods
(each a declared op with its arguments, types and answer, sending exactly that line), the `Settings` a
bot is started with, the `Observation` and its `Status`, and the lines out the player reads. Each check
is also run on a deliberately broken copy, to show that it fails. On a real bot (the lockstep clock): a
request outside the declaration is refused, and before its login the bot answers nothing but the login
op."""

from __future__ import annotations

import asyncio
import inspect
import json
import re
import shutil
import subprocess
import typing
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
import pytest_asyncio

from pillagerbench.host.node import JS_DIR, node_binary, node_env
from pillagerbench.players import Player, PlayerError
from pillagerbench.players.bot_protocol import (
    DECLARATION,
    POSTED,
    PROTOCOL,
    BotOps,
    Declaration,
    Settings,
    read_protocol,
    request_line,
)
from pillagerbench.players.channel import bot_command
from pillagerbench.players.observation import Observation, Status
from pillagerbench.server import ArenaServer
from pillagerbench.server.seams import UndeclaredOp
from tests.support.declared_ops import method_problems, typed_methods

NOT_OPS = {"send"}  # BotOps' own: the channel's one line
NOT_WIRE = {"rid", "wait"}  # a run's id (the player's, set before it is sent) and a reply's wait
SETTINGS: Settings = {"host": "127.0.0.1", "port": 1, "username": "proto", "primitives": None}
SETTINGS |= {"heartbeatMs": 200, "clock": "lockstep", "cue": True}


class Recording(BotOps):
    """BotOps that keeps the lines it was asked to send (a reply is None at once)."""

    def __init__(self) -> None:
        self.lines: list[dict] = []
        self.ids = iter(range(1, 1000))

    def next_id(self) -> int:
        return next(self.ids)

    async def send(self, msg: dict) -> None:
        self.lines.append(msg)

    async def _exchange(self, rid: int, line: dict, wait: float) -> Any:
        await self.send(line)


async def sending_problems(name: str, method: Callable, answer: str) -> list[str]:
    """The line the method sends, given a distinct value for each of its wire parameters, against its own
    name and parameters (with an id, unless its op is answered by the spawned line)."""
    params = [p for p in list(inspect.signature(method).parameters)[1:] if p not in NOT_WIRE]
    values = {p: f"<{p}>" for p in params}
    bot = Recording()
    await method(bot, **values, **({"rid": 99} if "rid" in inspect.signature(method).parameters else {}))
    rid = {"spawned": {}, "run": {"id": 99}}.get(answer, {"id": 1})
    wanted = [rid | {"op": name} | values]
    return [] if bot.lines == wanted else [f"{name}: sends {bot.lines}, should send {wanted}"]


async def python_problems(cls: type, protocol: Declaration) -> list[str]:
    methods = typed_methods(cls, NOT_OPS)
    problems = [f"op {op} is declared but BotOps has no method for it" for op in protocol.ops if op not in methods]
    for name, method in methods.items():
        if name not in protocol.ops:
            problems.append(f"BotOps.{name} is not a declared op")
            continue
        answers = "None" if name in POSTED else None
        problems += method_problems(
            name, method, protocol.ops[name], protocol.types, not_wire=NOT_WIRE, answers=answers
        )
        problems += await sending_problems(name, method, protocol.answers[name])
    return problems


def field_problems(typed: type, fields: dict[str, str], types: dict[str, dict[str, str]]) -> list[str]:
    """How a TypedDict differs from declared fields (name -> type): names and Python annotations."""
    annotations = {k: v for c in reversed(typed.__mro__) for k, v in getattr(c, "__annotations__", {}).items()}
    hints = {k: getattr(v, "__forward_arg__", v) for k, v in annotations.items()}
    problems = [f"{typed.__name__}.{k} is not declared" for k in hints.keys() - fields.keys()]
    problems += [f"{typed.__name__} has no {k}" for k in fields.keys() - hints.keys()]
    for k in hints.keys() & fields.keys():
        declared = types[fields[k].removesuffix("?")]["python"] + (" | None" if fields[k].endswith("?") else "")
        if hints[k] != declared:
            problems.append(f"{typed.__name__}.{k} is {hints[k]}, declared {declared}")
    return problems


def settings_problems(protocol: Declaration) -> list[str]:
    """The Settings TypedDict against the declared settings: fields, types, which are required."""
    problems = field_problems(Settings, protocol.settings, protocol.types)
    required = {k for k, t in protocol.settings.items() if not t.endswith("?")}
    if Settings.__required_keys__ != required:
        problems.append(f"Settings requires {sorted(Settings.__required_keys__)}, declared {sorted(required)}")
    return problems


def observation_problems(protocol: Declaration) -> list[str]:
    return field_problems(Observation, protocol.observation, protocol.types) + field_problems(
        Status, protocol.status, protocol.types
    )


def lines_problems(protocol: Declaration) -> list[str]:
    """Each declared line out (its example) is read by the player, not taken for a reply."""
    player = Player("lines", 1)
    answered: list[dict] = []
    player.channel.answer = answered.append  # type: ignore[method-assign]
    player.bot._spawned = asyncio.get_running_loop().create_future()
    for kind, example in protocol.lines.items():
        player.bot._dispatch({kind: example})
    return [f"line {msg} is not read by the player" for msg in answered]


def broken_declaration(path: Path) -> None:
    """A copy of the declaration with an op gone (memory), one added (nap), an argument renamed (settle's
    pos), one made required (lag's reset), an answer changed (observe's) and login answered by a reply;
    a setting renamed (heartbeatMs) and one retyped (cue); a status field gone (biome), one added
    (hunger), one retyped (yaw); a line out added (nap)."""
    data = json.loads(DECLARATION.read_text(encoding="utf-8"))
    ops = data["ops"]
    del ops["memory"]
    ops["nap"] = {"doc": "Sleep.", "args": {"seconds": "number"}, "result": "boolean"}
    ops["settle"]["args"] = {"at": "pos?", "timeout": "number?"}
    ops["lag"]["args"]["reset"] = "boolean"
    ops["observe"]["result"] = "lag"
    del ops["login"]["answer"]
    data["settings"]["heartbeat"] = data["settings"].pop("heartbeatMs")
    data["settings"]["cue"]["type"] = "string?"
    del data["status"]["biome"]
    data["status"] |= {"hunger": "number", "yaw": "integer"}
    data["lines"]["nap"] = {"doc": "Asleep.", "example": 1}
    path.write_text(json.dumps(data), encoding="utf-8")


def start_bot(main: Path, settings: dict) -> subprocess.CompletedProcess:
    """main.js started with `settings` and its stdin closed: a bot that starts waits for its login,
    and ends (code 0) when its stdin closes first."""
    return subprocess.run(
        [str(node_binary()), str(main), json.dumps(settings)],
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        env=node_env(),
        timeout=60,
    )


# ---- the declaration and the two sides agree ----


def test_the_bot_starts_with_its_handlers_and_settings_as_declared():
    command = bot_command(SETTINGS)  # as a player starts it, under the permission model
    proc = subprocess.run(command, stdin=subprocess.DEVNULL, capture_output=True, text=True, env=node_env(), timeout=60)
    assert proc.returncode == 0 and "[bot]" not in proc.stderr, proc.stderr


async def test_every_typed_method_is_a_declared_op_with_its_arguments():
    assert await python_problems(BotOps, PROTOCOL) == []
    assert len(typed_methods(BotOps, NOT_OPS)) == len(PROTOCOL.ops) == 14


async def test_settings_observation_and_lines_are_as_declared():
    assert settings_problems(PROTOCOL) == []
    assert observation_problems(PROTOCOL) == []
    assert lines_problems(PROTOCOL) == []
    assert typing.get_type_hints(Settings)  # the annotations resolve (mypy reads the same)


def test_an_undeclared_op_or_argument_is_not_sent():
    with pytest.raises(UndeclaredOp, match="nap"):
        request_line("nap", {}, 1)
    with pytest.raises(UndeclaredOp, match=r"settle\(at\)"):
        request_line("settle", {"at": [0, 4, 0]}, 1)
    with pytest.raises(UndeclaredOp, match=r"run\(timeout\)"):  # code is required
        request_line("run", {"timeout": 3}, 1)
    assert request_line("clear", {"seed": None}, 4) == {"id": 4, "op": "clear"}  # None is not sent


# ---- and the checks fail where they should ----


def test_the_bot_does_not_start_with_a_broken_declaration(tmp_path):
    shutil.copytree(JS_DIR / "bot", tmp_path / "bot")
    shutil.copytree(JS_DIR / "clock", tmp_path / "clock")  # what main.js requires beside it
    broken_declaration(tmp_path / "bot" / "bot_protocol.json")
    proc = start_bot(tmp_path / "bot" / "main.js", SETTINGS)
    assert proc.returncode == 2
    assert '[bot] settings: "heartbeatMs" is not declared (declared: ' in proc.stderr
    assert '[bot] settings: "cue" must be a string, got true' in proc.stderr
    fitting = {k: v for k, v in SETTINGS.items() if k != "heartbeatMs"} | {"heartbeat": 200, "cue": "yes"}
    proc = start_bot(tmp_path / "bot" / "main.js", fitting)
    assert proc.returncode == 2, proc.stderr
    problems = [line for line in proc.stderr.splitlines() if line.startswith("[bot] ")]
    assert problems == [
        "[bot] op login is declared but has no handler (answered by reply)",
        "[bot] op nap is declared but has no handler (answered by reply)",
        "[bot] op memory has a handler but is not declared",
        "[bot] op login is answered by spawned, declared reply",
    ]


async def test_python_disagrees_with_a_broken_declaration(tmp_path):
    broken_declaration(tmp_path / "bot_protocol.json")
    broken = read_protocol(tmp_path / "bot_protocol.json")
    problems = await python_problems(BotOps, broken)
    assert "op nap is declared but BotOps has no method for it" in problems
    assert "BotOps.memory is not a declared op" in problems
    assert "settle: arguments ['pos', 'timeout'], declared ['at', 'timeout']" in problems
    assert "lag: argument reset is required" in problems
    assert "lag: argument reset is bool | None, declared bool" in problems
    assert "observe: answers Observation, declared LagReport" in problems
    assert any(p.startswith("login: sends [{'op': 'login'}]") for p in problems)  # a reply would have an id
    assert len(problems) == 7, problems
    assert sorted(settings_problems(broken)) == [
        "Settings has no heartbeat",
        "Settings.cue is bool | None, declared str | None",
        "Settings.heartbeatMs is not declared",
    ]
    assert sorted(observation_problems(broken)) == [
        "Status has no hunger",
        "Status.biome is not declared",
        "Status.yaw is float, declared int",
    ]
    assert lines_problems(broken) == ["line {'nap': 1} is not read by the player"]


# ---- a real bot refuses what is not declared ----


@pytest_asyncio.fixture(scope="module", loop_scope="session")
async def server():
    srv = ArenaServer(crop_growth_chance=0.0, clock="lockstep")
    await srv.start()
    await srv.clock(unpaced=True)
    yield srv
    await srv.stop()


async def test_a_bot_refuses_requests_outside_the_declaration(server, tmp_path):
    player = Player("proto1", server.port, server=server, log_dir=tmp_path, clock="lockstep")
    await player.start()
    try:
        channel = player.channel
        refused = {
            "nap": 'unknown op "nap" (valid: login, ping, permissions, memory, run, stop, observe, lag, clear, equip, settle, act, hud, view)',
            "settle": 'op settle: "at" is not declared (declared: pos, timeout)',
            "clear": 'op clear: "seed" must be an integer, got "three"',
            "run": 'op run: "code" is missing',
            "login": "op login: already logged in",
        }
        lines = {"nap": {}, "settle": {"at": [0, 4, 0]}, "clear": {"seed": "three"}, "run": {}, "login": {}}
        for op, error in refused.items():
            rid = channel.next_id()
            with pytest.raises(PlayerError, match=f"^{re.escape(f'proto1: {error}')}$"):
                await channel._exchange(rid, {"id": rid, "op": op, **lines[op]}, 10)
        assert await channel.ping() == "pong"  # and goes on answering
    finally:
        await player.close()


async def test_before_its_login_a_bot_answers_only_the_login_op(server, tmp_path):
    player = Player("proto2", server.port, server=server, log_dir=tmp_path, clock="lockstep")
    await player.launch()
    try:
        with pytest.raises(
            PlayerError, match=re.escape("proto2: op ping: not logged in yet (the first request is login)")
        ):
            await player.channel.ping()
        rid = player.channel.next_id()
        with pytest.raises(PlayerError, match=re.escape('proto2: unknown op "nap" (valid: login, ping, ')):
            await player.channel._exchange(rid, {"id": rid, "op": "nap"}, 10)
        assert "proto2" not in {p["name"] for p in await server.players()}
        await player.start()  # the login op: it logs in
        assert player.bot.alive and await player.channel.ping() == "pong"
        assert "proto2" in {p["name"] for p in await server.players()}
    finally:
        await player.close()
