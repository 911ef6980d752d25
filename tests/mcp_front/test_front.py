"""The MCP front (`pillagerbench.mcp_front.serve`) driven by the official SDK's own client over real
transports: stdio (a subprocess running tests/mcp_front/echo_server.py) and streamable HTTP (in process,
with a token). Tools are listed as declared, calls answered, failures come back as tool errors, the
caller's clientInfo reaches the callback, and two calls in flight at once run concurrently."""

from __future__ import annotations

import asyncio
import contextlib
import sys
import time
from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import httpx2
import pytest
from mcp import ClientSession, StdioServerParameters
from mcp.client.stdio import stdio_client
from mcp.client.streamable_http import streamable_http_client
from mcp.shared.exceptions import MCPError
from mcp.types import CallToolResult, Implementation, TextContent

from pillagerbench.mcp_front import serve
from tests.mcp_front.echo_server import TOOLS, answer

ECHO_SERVER = Path(__file__).with_name("echo_server.py")
ROOT = Path(__file__).resolve().parents[2]
CLIENT = Implementation(name="test-client", version="1.2.3")
TOKEN = "s3cret-token"


async def _call(session: ClientSession, name: str, arguments: dict[str, Any]) -> CallToolResult:
    result = await session.call_tool(name, arguments)
    assert isinstance(result, CallToolResult)
    return result


def _text(result: CallToolResult) -> str:
    assert len(result.content) == 1 and isinstance(result.content[0], TextContent)
    return result.content[0].text


async def _check_tools(session: ClientSession) -> None:
    """Listed as declared; echo answered with the caller; unknown, refusing and raising tools are tool errors."""
    listed = await session.list_tools()
    assert [(t.name, t.description, t.input_schema) for t in listed.tools] == [
        (s.name, s.description, s.parameters) for s in TOOLS
    ]
    echo = await _call(session, "echo", {"text": "hello"})
    assert not echo.is_error and _text(echo) == "hello (from test-client 1.2.3)"
    assert echo.structured_content == {"text": "hello", "caller": {"name": "test-client", "version": "1.2.3"}}
    unknown = await _call(session, "fly", {})
    assert unknown.is_error and "'fly'" in _text(unknown) and "echo, slow, refuse, boom" in _text(unknown)
    refused = await _call(session, "refuse", {})
    assert refused.is_error and _text(refused) == "refused: not your turn"
    boom = await _call(session, "boom", {})
    assert boom.is_error and _text(boom) == "tool 'boom' failed: RuntimeError: kaboom"
    assert not (await _call(session, "echo", {"text": "still up"})).is_error


async def _two_slow_calls(session: ClientSession, seconds: float) -> float:
    start = time.monotonic()
    both = await asyncio.gather(*(_call(session, "slow", {"seconds": seconds}) for _ in range(2)))
    assert [_text(r) for r in both] == [f"slept {seconds}"] * 2
    return time.monotonic() - start


async def test_stdio_lists_calls_and_knows_the_caller() -> None:
    params = StdioServerParameters(command=sys.executable, args=[str(ECHO_SERVER)], cwd=ROOT)
    async with stdio_client(params) as (read, write), ClientSession(read, write, client_info=CLIENT) as session:
        await session.initialize()
        await _check_tools(session)
        assert await _two_slow_calls(session, 0.5) < 0.9


@contextlib.asynccontextmanager
async def _http_server(token: str | None = TOKEN) -> AsyncIterator[str]:
    """`serve` over HTTP in this process on a free port; yields its URL, stops it on the way out."""
    stop = asyncio.Event()
    ready: asyncio.Future[str] = asyncio.get_running_loop().create_future()
    task = asyncio.create_task(
        serve(TOOLS, answer, transport="http", port=0, token=token, on_ready=ready.set_result, stop=stop)
    )
    await asyncio.wait([ready, task], timeout=5, return_when=asyncio.FIRST_COMPLETED)
    assert ready.done(), f"the server did not start: {task}"
    try:
        yield ready.result()
    finally:
        stop.set()
        await asyncio.wait_for(task, 5)


@contextlib.asynccontextmanager
async def _http_session(url: str, token: str | None) -> AsyncIterator[ClientSession]:
    headers = {"Authorization": f"Bearer {token}"} if token is not None else {}
    async with (
        httpx2.AsyncClient(headers=headers, timeout=httpx2.Timeout(10)) as http,
        streamable_http_client(url, http_client=http) as (read, write),
        ClientSession(read, write, client_info=CLIENT) as session,
    ):
        yield session


async def test_http_needs_the_token_and_serves_concurrently() -> None:
    async with _http_server() as url:
        assert url.startswith("http://127.0.0.1:") and url.endswith("/mcp")
        async with httpx2.AsyncClient() as http:
            for headers in ({}, {"Authorization": "Bearer wrong"}, {"Authorization": TOKEN}):
                refused = await http.post(url, json={"jsonrpc": "2.0", "id": 1, "method": "ping"}, headers=headers)
                assert refused.status_code == 401
        async with _http_session(url, None) as session:
            with pytest.raises(MCPError, match="unauthorized"):
                await session.initialize()
        async with _http_session(url, TOKEN) as session:
            await session.initialize()
            await _check_tools(session)
            assert await _two_slow_calls(session, 1.0) < 1.6


async def test_http_modern_protocol_caller_from_the_envelope() -> None:
    """The 2026 protocol has no handshake: each request carries the clientInfo, and the caller is read from it."""
    async with _http_server(token=None) as url, _http_session(url, None) as session:
        await session.discover()
        echo = await _call(session, "echo", {"text": "hi"})
        assert _text(echo) == "hi (from test-client 1.2.3)"


async def test_non_loopback_host_needs_a_token() -> None:
    with pytest.raises(ValueError, match="non-loopback host '0.0.0.0' without a token"):
        await serve(TOOLS, answer, transport="http", host="0.0.0.0")
    with pytest.raises(ValueError, match="unknown MCP transport"):
        await serve(TOOLS, answer, transport="sse")
