"""The control channel's ops are declared once (js/server/control_ops.json) and both sides agree with it:
every declared op has a handler in control.js and every handler is declared (control.js refuses to load
otherwise; Node is asked here), and every typed method of Python's `Control` is a declared op with the
declared arguments, types and answer, and sends exactly those. Each check is also run on a
deliberately broken copy, to show that it fails."""

from __future__ import annotations

import inspect
import json
import shutil
import subprocess
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from pillagerbench.host.node import JS_DIR, node_binary, node_env
from pillagerbench.server.seams import DECLARATION, OPS, TYPES, Control, OpSpec, UndeclaredOp, read_declaration
from tests.support.declared_ops import method_problems, typed_methods

NOT_OPS = {"request", "send"}  # Control's own methods: the channel and the sending of a declared op


class Recording(Control):
    """A Control that keeps what it was asked to send."""

    def __init__(self) -> None:
        self.sent: list[tuple[str, dict[str, Any]]] = []
        self.timeouts: dict[str, float | None] = {}  # op -> the reply timeout it was sent with

    async def request(self, op: str, timeout: float | None = 30, **args: Any) -> Any:
        self.sent.append((op, args))
        self.timeouts[op] = timeout


async def sending_problems(name: str, method: Callable, control: Recording) -> list[str]:
    """What the method sends, given a distinct value for each of its parameters, against its own
    name and parameters."""
    params = list(inspect.signature(method).parameters)[1:]
    values = {p: f"<{p}>" for p in params}
    control.sent.clear()
    await method(control, **values)
    wanted = [(name, {p.removesuffix("_"): v for p, v in values.items()})]
    return [] if control.sent == wanted else [f"{name}: sends {control.sent}, should send {wanted}"]


async def python_problems(cls: type, ops: dict[str, OpSpec], types: dict[str, dict[str, str]]) -> list[str]:
    methods = typed_methods(cls, NOT_OPS)
    problems = [f"op {op} is declared but Control has no method for it" for op in ops if op not in methods]
    control = Recording()  # each method sends through it, whichever class it comes from
    for name, method in methods.items():
        if name not in ops:
            problems.append(f"Control.{name} is not a declared op")
            continue
        problems += method_problems(name, method, ops[name], types)
        problems += await sending_problems(name, method, control)
    return problems


# The op table control.js exports, in its order (it throws when loading if it disagrees with the declaration)
HANDLERS = r"""
const { OPS } = require(process.argv[1] + '/control.js')
console.log(JSON.stringify(Object.keys(OPS)))
"""


def js_handlers(server_dir: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [str(node_binary()), "-e", HANDLERS, str(server_dir)],
        capture_output=True,
        text=True,
        env=node_env(),
        timeout=60,
    )


def broken_declaration(path: Path) -> None:
    """A copy of the declaration with an op gone (tell), one added (nap), an argument renamed
    (set_block's block), one made required (give's count) and an answer changed (get_block's)."""
    data = json.loads(DECLARATION.read_text(encoding="utf-8"))
    ops = data["ops"]
    del ops["tell"]
    ops["nap"] = {"doc": "Sleep.", "args": {"seconds": "number"}, "result": "boolean"}
    ops["set_block"]["args"] = {"pos": "pos", "name": "string", "properties": "properties?"}
    ops["give"]["args"]["count"] = "integer"
    ops["get_block"]["result"] = "slots"
    path.write_text(json.dumps(data), encoding="utf-8")


# ---- the declaration and the two sides agree ----


def test_every_js_handler_is_a_declared_op_and_back():
    proc = js_handlers(JS_DIR / "server")
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout) == list(OPS)  # the same ops, in the same order (the "valid: ..." list)


async def test_an_op_that_waits_is_sent_without_a_reply_timeout():
    control = Recording()
    await control.wait_tick(7)
    await control.hold("red")
    assert control.timeouts == {"wait_tick": None, "hold": 30}


async def test_every_python_method_is_a_declared_op_with_its_arguments():
    assert await python_problems(Control, OPS, TYPES) == []
    assert len(typed_methods(Control, NOT_OPS)) == len(OPS) == 43


# ---- and the checks fail where they should ----


def test_control_js_does_not_load_with_a_broken_declaration(tmp_path):
    server_dir = tmp_path / "server"
    shutil.copytree(JS_DIR / "server", server_dir)
    shutil.copytree(JS_DIR / "clock", tmp_path / "clock")  # what control.js requires beside it
    broken_declaration(server_dir / "control_ops.json")
    proc = js_handlers(server_dir)
    assert proc.returncode != 0
    assert "op nap is declared but has no handler" in proc.stderr
    assert "op tell has a handler but is not declared" in proc.stderr


async def test_python_methods_disagree_with_a_broken_declaration(tmp_path):
    broken_declaration(tmp_path / "control_ops.json")
    ops, types = read_declaration(tmp_path / "control_ops.json")
    problems = await python_problems(Control, ops, types)
    assert "op nap is declared but Control has no method for it" in problems
    assert "Control.tell is not a declared op" in problems
    assert "set_block: arguments ['block', 'pos', 'properties'], declared ['name', 'pos', 'properties']" in problems
    assert "give: argument count is required" in problems
    assert "give: argument count is int | None, declared int" in problems
    assert "get_block: answers BlockState, declared list[Slot]" in problems
    assert len(problems) == 6, problems


class Broken(Recording):
    """Typed methods gone wrong: an undeclared op, a wrong type, a renamed argument sent, one not sent."""

    async def nap(self, seconds: float) -> bool:
        return await self.send("nap", seconds=seconds)

    async def tick_rate(self, tps: int) -> bool:  # type: ignore[override]
        return await self.send("tick_rate", tps=tps)

    async def chat(self, message: str) -> bool:
        return await self.request("chat", text=message)

    async def teleport(self, player: str, pos: Any, yaw: float | None = None, pitch: float | None = None) -> bool:
        return await self.send("teleport", player=player, pos=pos)


async def test_broken_python_methods_are_caught():
    problems = await python_problems(Broken, OPS, TYPES)
    assert "Control.nap is not a declared op" in problems
    assert "tick_rate: argument tps is int, declared float" in problems
    assert "chat: sends [('chat', {'text': '<message>'})], should send [('chat', {'message': '<message>'})]" in problems
    assert "teleport: argument pos is Any, declared Pos" in problems
    assert any(p.startswith("teleport: sends") for p in problems)  # yaw and pitch not sent
    assert len(problems) == 5, problems


async def test_an_undeclared_op_or_argument_is_not_sent():
    control = Recording()
    with pytest.raises(UndeclaredOp, match="nap"):
        await control.send("nap")
    with pytest.raises(UndeclaredOp, match=r"set_block\(pos, colour\)"):
        await control.send("set_block", pos=[0, 4, 0], colour="red")
    assert control.sent == []
    await control.give("alice", "bread")  # an optional argument left as None is not sent
    assert control.sent == [("give", {"player": "alice", "item": "bread"})]
