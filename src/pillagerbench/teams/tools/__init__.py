"""The game as tools (docs/any-agent.md): the declared tool surface (`surface.py`, `spec.py`), the seat an
outside agent plays a team from (`seat.py`), the team it plays (`agent.py`: `agent`), and our own
tool-calling LLM team (`tools`)."""

from pillagerbench.teams.tools.agent import SEATS, AgentTeam, open_seat, reserve_seat
from pillagerbench.teams.tools.llm_team import ToolsTeam
from pillagerbench.teams.tools.seat import Seat
from pillagerbench.teams.tools.spec import ToolResult, ToolSpec
from pillagerbench.teams.tools.surface import briefing, tools_of

__all__ = [
    "SEATS",
    "AgentTeam",
    "Seat",
    "ToolResult",
    "ToolSpec",
    "ToolsTeam",
    "briefing",
    "open_seat",
    "reserve_seat",
    "tools_of",
]
