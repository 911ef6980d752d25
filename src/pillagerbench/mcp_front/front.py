"""Serve a declared list of tools over MCP: one `ToolSpec` per tool (its JSON schema listed as given) and
one callback answering every call, on stdio or on streamable HTTP, through the low-level server of the
official `mcp` SDK (2.x). The tools are data, not Python functions, hence the low-level server.

Every tool call runs in a task of its own (the SDK's JSON-RPC dispatcher spawns one per request), so
two calls in flight at once are served concurrently. A failing call (an unknown tool, a refusal, a
raising callback) is answered as a tool error (`isError: true`) and the server goes on."""

from __future__ import annotations

import asyncio
import contextlib
import hmac
import importlib.metadata
import json
import socket
from collections.abc import Awaitable, Callable, Generator, Mapping
from dataclasses import dataclass
from typing import Any

import mcp.types as types
import uvicorn
from mcp.server.context import ServerRequestContext
from mcp.server.lowlevel import Server
from mcp.server.stdio import stdio_server
from mcp.server.streamable_http_manager import StreamableHTTPASGIApp, StreamableHTTPSessionManager
from mcp.server.transport_security import TransportSecuritySettings
from starlette.applications import Starlette
from starlette.routing import Route
from starlette.types import ASGIApp, Receive, Scope, Send

from pillagerbench.teams.tools.spec import ToolResult, ToolSpec

LOOPBACK_HOSTS = ("127.0.0.1", "::1", "localhost")
MCP_PATH = "/mcp"
GRACEFUL_SHUTDOWN_SECONDS = 2  # open HTTP streams (a client's SSE stream) are cut after this once `stop` is set


@dataclass(frozen=True)
class Caller:
    """The client's declared `clientInfo` (from its initialize request, or the per-request envelope of the
    2026 protocol); `unknown`/`0` when it declared none."""

    name: str
    version: str


ToolCall = Callable[[Caller, str, dict[str, Any]], Awaitable[ToolResult]]


async def serve(
    tools: list[ToolSpec],
    call: ToolCall,
    *,
    transport: str = "stdio",
    host: str = "127.0.0.1",
    port: int = 0,
    token: str | None = None,
    name: str = "pillagerbench",
    on_ready: Callable[[str], None] | None = None,
    stop: asyncio.Event | None = None,
    on_session_end: Callable[[], None] | None = None,
) -> None:
    """Serve `tools` over MCP, answering each call with `call(caller, tool name, arguments)`.
    `on_session_end`: called when an HTTP client's session ends (it closed it, or its connection went);
    on stdio the client's leaving is this function's return.

    transport="stdio": on this process's stdin/stdout until the client disconnects (`host`, `port`,
    `token` and `stop` are not used; `on_ready` gets "stdio"). transport="http": streamable HTTP at
    `/mcp` on host:port (port 0 = a free one) until `stop` is set (or the task is cancelled); `on_ready`
    gets the real URL once listening. With `token`, every HTTP request must carry
    `Authorization: Bearer <token>` or gets 401; a host that is not loopback needs a token."""
    if transport not in ("stdio", "http"):
        raise ValueError(f"unknown MCP transport {transport!r}: use 'stdio' or 'http'")
    if transport == "http":
        _check_host(host, token)
    server = _build_server(tools, call, name)
    if transport == "stdio":
        async with stdio_server() as (read, write):
            if on_ready is not None:
                on_ready("stdio")
            await server.run(read, write, server.create_initialization_options())
        return
    await _serve_http(server, host, port, token, on_ready, stop, on_session_end)


class _Sessions(StreamableHTTPSessionManager):
    """The SDK's HTTP session manager, saying when a session has ended (a client's DELETE, its connection
    gone, a crash): the one place every session's end passes (the SDK's pinned 2.3.0)."""

    def __init__(self, *args: Any, on_end: Callable[[], None] | None = None, **kwargs: Any):
        super().__init__(*args, **kwargs)
        self._on_end = on_end

    async def _discard_session(self, session_id: str, transport: Any) -> None:
        known = session_id in self._server_instances
        await super()._discard_session(session_id, transport)
        if known and self._on_end is not None:
            self._on_end()


def _check_host(host: str, token: str | None) -> None:
    """Refuse (ValueError) an empty token, and a host that is not loopback without a token."""
    if token is not None and not token:
        raise ValueError("the MCP token is empty: pass a real token, or None on a loopback host")
    if token is None and host not in LOOPBACK_HOSTS:
        raise ValueError(
            f"refusing to serve MCP on non-loopback host {host!r} without a token: pass a token, "
            f"or use one of {', '.join(LOOPBACK_HOSTS)}"
        )


def _build_server(tools: list[ToolSpec], call: ToolCall, name: str) -> Server[dict[str, Any]]:
    """The SDK's low-level server listing `tools` as declared and answering calls through `call`."""
    listed = types.ListToolsResult(
        tools=[types.Tool(name=t.name, description=t.description, input_schema=t.parameters) for t in tools]
    )
    known = [t.name for t in tools]

    async def list_tools(
        ctx: ServerRequestContext[dict[str, Any]], params: types.PaginatedRequestParams | None
    ) -> types.ListToolsResult:
        return listed

    async def call_tool(
        ctx: ServerRequestContext[dict[str, Any]], params: types.CallToolRequestParams
    ) -> types.CallToolResult:
        return await _answer(call, _caller_of(ctx), known, params.name, dict(params.arguments or {}))

    return Server(name, version=_version(), on_list_tools=list_tools, on_call_tool=call_tool)


async def _answer(
    call: ToolCall, caller: Caller, known: list[str], tool: str, arguments: dict[str, Any]
) -> types.CallToolResult:
    """One tool call as its MCP result: an unknown tool and a raising callback become tool errors."""
    if tool not in known:
        return _error(f"unknown tool {tool!r}; the tools are: {', '.join(known) or '(none)'}")
    try:
        result = await call(caller, tool, arguments)
    except Exception as exc:  # noqa: BLE001 - any failure of one call is that call's tool error; the server goes on
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else "(no message)"
        return _error(f"tool {tool!r} failed: {type(exc).__name__}: {first}")
    return types.CallToolResult(
        content=[types.TextContent(type="text", text=result.text)],
        structured_content=result.data or None,
        is_error=result.error,
    )


def _error(text: str) -> types.CallToolResult:
    return types.CallToolResult(content=[types.TextContent(type="text", text=text)], is_error=True)


def _caller_of(ctx: ServerRequestContext[dict[str, Any]]) -> Caller:
    """The client's declared clientInfo: the handshake's (2025 protocol), else this request's envelope."""
    params = ctx.session.client_params
    if params is not None:
        return Caller(params.client_info.name or "unknown", params.client_info.version or "0")
    meta = (ctx.params or {}).get("_meta")
    info = meta.get(types.CLIENT_INFO_META_KEY) if isinstance(meta, Mapping) else None
    if isinstance(info, Mapping):
        return Caller(str(info.get("name") or "unknown"), str(info.get("version") or "0"))
    return Caller("unknown", "0")


def _version() -> str:
    try:
        return importlib.metadata.version("pillagerbench")
    except importlib.metadata.PackageNotFoundError:
        return "0"


class _Gate:
    """ASGI middleware in front of the SDK's app. With a token, an HTTP request without
    `Authorization: Bearer <token>` gets 401; once `closing` is set (the server is stopping), every
    HTTP request gets 503. Both carry a JSON-RPC error body, so the SDK's client shows the message."""

    def __init__(self, app: ASGIApp, token: str | None) -> None:
        self._app = app
        self._token = token.encode() if token is not None else None
        self.closing = False

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http" and self.closing:
            await _refuse(send, 503, -32000, "the MCP server is shutting down")
        elif scope["type"] == "http" and not self._allowed(scope):
            await _refuse(send, 401, -32001, "unauthorized: this MCP server needs 'Authorization: Bearer <token>'")
        else:
            await self._app(scope, receive, send)

    def _allowed(self, scope: Scope) -> bool:
        if self._token is None:
            return True
        value = next((v for k, v in scope["headers"] if k.lower() == b"authorization"), b"")
        scheme, _, credential = bytes(value).partition(b" ")
        return scheme.lower() == b"bearer" and hmac.compare_digest(credential.strip(), self._token)


async def _refuse(send: Send, status: int, code: int, message: str) -> None:
    body = json.dumps({"jsonrpc": "2.0", "id": None, "error": {"code": code, "message": message}}).encode()
    headers = [(b"content-type", b"application/json")]
    if status == 401:
        headers.append((b"www-authenticate", b"Bearer"))
    await send({"type": "http.response.start", "status": status, "headers": headers})
    await send({"type": "http.response.body", "body": body})


class _HostedUvicorn(uvicorn.Server):
    """uvicorn, leaving the host process's signal handlers alone: `stop` ends it, not Ctrl-C."""

    @contextlib.contextmanager
    def capture_signals(self) -> Generator[None, None, None]:
        yield


async def _serve_http(
    server: Server[dict[str, Any]],
    host: str,
    port: int,
    token: str | None,
    on_ready: Callable[[str], None] | None,
    stop: asyncio.Event | None,
    on_session_end: Callable[[], None] | None = None,
) -> None:
    """uvicorn serving the SDK's streamable HTTP session manager. On `stop` the manager is closed first
    (ending every MCP session and its open streams), then uvicorn, so the shutdown does not wait on a
    client's open SSE stream."""
    manager = _Sessions(app=server, security_settings=_security(host), on_end=on_session_end)
    gate = _Gate(Starlette(routes=[Route(MCP_PATH, endpoint=StreamableHTTPASGIApp(manager))]), token)
    config = uvicorn.Config(
        gate,
        lifespan="off",  # the session manager runs around uvicorn, not in its lifespan
        log_config=None,  # leave the host process's logging alone
        log_level="warning",
        access_log=False,
        timeout_graceful_shutdown=GRACEFUL_SHUTDOWN_SECONDS,
    )
    web = _HostedUvicorn(config)
    sock = _listen(host, port)
    stopping = asyncio.ensure_future(stop.wait() if stop is not None else asyncio.Event().wait())
    running: asyncio.Task[None] | None = None
    try:
        async with manager.run():
            try:
                running = asyncio.create_task(web.serve(sockets=[sock]))
                await _until_started(web, running, f"{host}:{port}")
                if on_ready is not None:
                    on_ready(_url(host, sock.getsockname()[1]))
                await asyncio.wait([running, stopping], return_when=asyncio.FIRST_COMPLETED)
            finally:
                gate.closing = True  # no request may reach the manager once it is closed
    finally:
        stopping.cancel()
        web.should_exit = True
        if running is not None:
            with contextlib.suppress(SystemExit):
                await asyncio.shield(running)
        sock.close()


def _security(host: str) -> TransportSecuritySettings | None:
    """DNS rebinding protection on a loopback host (what the SDK's `streamable_http_app` sets up)."""
    if host not in LOOPBACK_HOSTS:
        return None
    return TransportSecuritySettings(
        enable_dns_rebinding_protection=True,
        allowed_hosts=["127.0.0.1:*", "localhost:*", "[::1]:*"],
        allowed_origins=["http://127.0.0.1:*", "http://localhost:*", "http://[::1]:*"],
    )


async def _until_started(web: uvicorn.Server, running: asyncio.Task[None], where: str) -> None:
    while not web.started:
        if running.done():
            try:
                await running  # raises what made startup fail
            except SystemExit as exc:  # uvicorn exits on a failed application startup
                raise RuntimeError(f"the MCP HTTP server on {where} failed to start") from exc
            raise RuntimeError(f"the MCP HTTP server on {where} stopped while starting")
        await asyncio.sleep(0.01)


def _listen(host: str, port: int) -> socket.socket:
    """A listening TCP socket on host:port (port 0: a free one), bound before uvicorn starts so the
    real port is known."""
    family, kind, proto, _, address = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)[0]
    sock = socket.socket(family, kind, proto)
    try:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind(address)
        sock.listen()
        sock.setblocking(False)
    except OSError:
        sock.close()
        raise
    return sock


def _url(host: str, port: int) -> str:
    shown = f"[{host}]" if ":" in host else host
    return f"http://{shown}:{port}{MCP_PATH}"
