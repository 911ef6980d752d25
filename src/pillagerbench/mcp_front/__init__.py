"""The MCP front: serves the game's tools (declared as `ToolSpec`s) to any MCP client, on stdio or HTTP."""

from pillagerbench.mcp_front.front import Caller, ToolCall, serve

__all__ = ["Caller", "ToolCall", "serve"]
