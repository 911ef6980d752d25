"""The opponent model (paper §Opponent Model): from the second episode, the opponent team's
tactics inferred from what it said in chat (its players' lines, and the game's lines about it,
such as Dash & Dine's server announcing what it locked in), starting from "unknown". The answer
uses the same `[tactics]` tags as the tactics module (at most `max_items` items)."""

from __future__ import annotations

from pillagerbench.agents.asking import Asked, Chat, Whistle, ask

from .tactics import extract_tactics
from .templates import PROMPTS

ROLE = "opponent"
UNKNOWN = "unknown"


async def update(
    llm: Chat | None,
    *,
    opponent_team: str,
    opponent_players: list[str],
    objective: str,
    scenario: str,
    graph: str,
    chat_log: str,
    previous: str,
    attempts: int = 3,
    max_items: int = 3,
    deadline: Whistle | None = None,
) -> Asked[str]:
    messages = [
        {
            "role": "system",
            "content": PROMPTS["opponent_system"].render(
                opponent_team=opponent_team, objective=objective, scenario=scenario, causal_graph=graph
            ),
        },
        {
            "role": "user",
            "content": PROMPTS["opponent_user"].render(
                opponent_team=opponent_team,
                opponent_players=", ".join(opponent_players),
                chat_log=chat_log,
                previous=previous,
            ),
        },
    ]
    return await ask(
        llm,
        messages,
        role=ROLE,
        parse=lambda a: extract_tactics(a.text, max_items=max_items),
        attempts=attempts,
        retry=lambda p: PROMPTS["tactics_retry"].render(problem=p),
        deadline=deadline,
    )
