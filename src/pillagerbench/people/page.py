"""The people's page (docs/people.md), served by the match on loopback: the lobby (a name, the scenario's
description and map, ready) and the play view (the controls, the primitive buttons, chat, the score, the
clock and the events feed). Input comes as small JSON POSTs, the page polls its state; everything is
served from this package (page.html), nothing from the network."""

from __future__ import annotations

import asyncio
import contextlib
import re
import socket
from collections.abc import Generator
from importlib import resources
from typing import Any

import uvicorn
from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, Response
from starlette.routing import Route

from pillagerbench.people.relay import People, chat_code, code_of
from pillagerbench.people.seats import Refused

# the primitive buttons: name -> its arguments after `bot` (kind: item, count, player, block, position)
BUTTONS: dict[str, list[str]] = {
    "mineBlock": ["block", "count"],
    "craftItem": ["item", "count"],
    "smeltItem": ["item", "fuel", "count"],
    "placeItem": ["item", "position"],
    "giveToPlayer": ["item", "player", "count"],
    "killMob": ["mob", "seconds"],
    "depositItemIntoChest": ["position", "items"],
    "getItemFromChest": ["position", "items"],
}
WORD = re.compile(r"[A-Za-z_]{1,40}")


class _Hosted(uvicorn.Server):
    """uvicorn leaving the process's signal handlers alone."""

    @contextlib.contextmanager
    def capture_signals(self) -> Generator[None, None, None]:
        yield


def _args(kinds: list[str], given: list[Any]) -> list[Any]:
    if len(given) != len(kinds):
        raise Refused(f"{len(kinds)} arguments: {', '.join(kinds)}")
    out: list[Any] = []
    for kind, value in zip(kinds, given):
        if kind in ("count", "seconds"):
            out.append(int(value))
        elif kind == "position":
            out.append([float(v) for v in value])
        elif kind == "items":
            out.append({str(k): int(v) for k, v in dict(value).items()})
        elif isinstance(value, str) and WORD.fullmatch(value):
            out.append(value)
        else:
            raise Refused(f"{kind} {value!r}: a name")
    return out


def app(people: People, primitives: list[str]) -> Starlette:
    buttons = {k: v for k, v in BUTTONS.items() if any(p in primitives for p in (k, _module_of(k)))}

    async def body(request: Request) -> dict[str, Any]:
        try:
            data = await request.json()
        except ValueError:
            return {}
        return data if isinstance(data, dict) else {}

    def answer(fn):
        async def endpoint(request: Request) -> Response:
            try:
                return JSONResponse({"ok": True, "result": await fn(await body(request))})
            except Refused as exc:
                return JSONResponse({"ok": False, "error": str(exc)}, status_code=409)
            except (TypeError, ValueError) as exc:
                return JSONResponse({"ok": False, "error": f"bad request: {exc}"}, status_code=400)

        return endpoint

    async def join(data: dict) -> dict:
        seat = people.seats.take(str(data.get("name", "")), data.get("player"))
        people.say(f"{seat.person} took {seat.player} ({seat.side})")
        return {"token": seat.token, "player": seat.player}

    async def ready(data: dict) -> bool:
        people.ready(data.get("token"))
        return True

    async def act(data: dict) -> str:
        return await people.act(data.get("token"), dict(data.get("input") or {}))

    async def press(data: dict) -> bool:
        name = str(data.get("primitive"))
        if name not in buttons:
            raise Refused(f"no button {name!r} here (buttons: {', '.join(buttons)})")
        await people.program(data.get("token"), code_of(name, _args(buttons[name], list(data.get("args") or []))))
        return True

    async def chat(data: dict) -> bool:
        text = str(data.get("text", ""))[:256]
        await people.program(data.get("token"), chat_code(text))
        return True

    async def signal(data: dict) -> str:
        return await people.signal(data.get("token"), data.get("to"))

    async def state(request: Request) -> Response:
        return JSONResponse({**people.state(request.query_params.get("token")), "buttons": buttons})

    async def page(request: Request) -> Response:
        return HTMLResponse((resources.files("pillagerbench.people") / "page.html").read_text(encoding="utf-8"))

    async def layout(request: Request) -> Response:
        """The map of the layout played (people/lobby.py), or 404 while it is not known yet."""
        if not people.map_page:
            return HTMLResponse("no map yet: the episode's layout is drawn once it starts", status_code=404)
        return HTMLResponse(people.map_page)

    routes = [Route("/", page), Route("/state", state), Route("/map", layout)]
    posts = {"join": join, "ready": ready, "act": act, "press": press, "chat": chat, "signal": signal}
    routes += [Route(f"/{n}", answer(f), methods=["POST"]) for n, f in posts.items()]
    return Starlette(routes=routes)


def _module_of(primitive: str) -> str:
    return {"depositItemIntoChest": "useChest", "getItemFromChest": "useChest"}.get(primitive, primitive)


class PageServer:
    """The page on host:port (0: a free one), from `start` to `stop`."""

    def __init__(self, people: People, primitives: list[str], host: str = "127.0.0.1", port: int = 0):
        self.people, self.primitives, self.host, self.port = people, primitives, host, port
        self.url = ""
        self._server: _Hosted | None = None
        self._task: asyncio.Task | None = None

    async def start(self) -> str:
        sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind((self.host, self.port))
        config = uvicorn.Config(
            app(self.people, self.primitives), lifespan="off", log_config=None, log_level="warning", access_log=False
        )
        self._server = _Hosted(config)
        self._task = asyncio.create_task(self._server.serve(sockets=[sock]))
        while not self._server.started:
            if self._task.done():
                await self._task
            await asyncio.sleep(0.02)
        self.url = f"http://{self.host}:{sock.getsockname()[1]}/"
        return self.url

    async def stop(self) -> None:
        if self._server is not None and self._task is not None:
            self._server.should_exit = True
            with contextlib.suppress(Exception):
                await asyncio.wait_for(self._task, 5)
