"""A tiny MCP server for tests/mcp_front: `serve` with a few declared tools on stdio (run as a script),
and the same tools and callback for the in-process HTTP tests (imported)."""

from __future__ import annotations

import asyncio
from typing import Any

from pillagerbench.mcp_front import Caller, serve
from pillagerbench.teams.tools.spec import ToolResult, ToolSpec

TOOLS = [
    ToolSpec(
        "echo",
        "Say the text back, with who asked.",
        {"type": "object", "properties": {"text": {"type": "string"}}, "required": ["text"]},
    ),
    ToolSpec(
        "slow",
        "Wait some seconds, then answer.",
        {"type": "object", "properties": {"seconds": {"type": "number", "minimum": 0}}, "required": ["seconds"]},
        acting=True,
    ),
    ToolSpec("refuse", "Always refuses.", {"type": "object", "properties": {}}),
    ToolSpec("boom", "Always raises.", {"type": "object", "properties": {}}),
]


async def answer(caller: Caller, name: str, arguments: dict[str, Any]) -> ToolResult:
    if name == "echo":
        data = {"text": arguments["text"], "caller": {"name": caller.name, "version": caller.version}}
        return ToolResult(f"{arguments['text']} (from {caller.name} {caller.version})", data=data)
    if name == "slow":
        await asyncio.sleep(float(arguments["seconds"]))
        return ToolResult(f"slept {arguments['seconds']}")
    if name == "refuse":
        return ToolResult("refused: not your turn", error=True)
    if name == "boom":
        raise RuntimeError("kaboom\nsecond line")
    return ToolResult(f"no tool {name!r}", error=True)


if __name__ == "__main__":
    asyncio.run(serve(TOOLS, answer))
