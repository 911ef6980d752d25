"""The tactics module (paper §Tactics Module) and the tag format it shares with the opponent model.

Tactics are a numbered list of at most `max_items` short conditional actions naming players in
the third person, written between `[tactics]` and `[tactics end]`.

- First episode: generated from the team, its objective, the scenario and the causal graph
  (zero-shot chain of thought), unless a preset text is given.
- Later episodes: updated from last episode's events (the chat log, nearby blocks, every team
  member's inventory), the previous tactics, the causal graph and the opponent's tactics
  (few-shot chain of thought).

An answer without the tags is asked again (the problem is shown); after `attempts` calls the
caller keeps what it had.
"""

from __future__ import annotations

import re

from pillagerbench.agents.asking import Asked, Chat, Whistle, ask

from .templates import PROMPTS

ROLE = "tactics"
OPEN, CLOSE = "[tactics]", "[tactics end]"
_ITEM = re.compile(r"^\s*(\d+)[.)]\s+\S")


def extract_tactics(text: str, *, max_items: int = 6) -> str:
    """The tagged tactics in an answer (the last tagged part if there are several), numbered items
    only, at most `max_items` of them. Raises ValueError with the problem."""
    low = text.lower()
    start = low.rfind(OPEN)
    if start < 0:
        raise ValueError(f"the answer has no {OPEN} ... {CLOSE} part")
    end = low.find(CLOSE, start)
    body = text[start + len(OPEN) : end if end >= 0 else len(text)]
    lines = [ln.rstrip() for ln in body.strip().splitlines() if ln.strip()]
    if not lines:
        raise ValueError(f"the part between {OPEN} and {CLOSE} is empty")
    items: list[str] = []
    for ln in lines:
        if _ITEM.match(ln):
            items.append(ln.strip())
        elif items:  # a wrapped line belongs to the item above
            items[-1] += " " + ln.strip()
    if not items:
        if end < 0:
            raise ValueError(f"the answer has no {CLOSE} and no numbered tactics")
        return "\n".join(lines[:max_items])  # unnumbered but tagged: keep it as it is
    return "\n".join(items[:max_items])


def _retry(problem: str) -> str:
    return PROMPTS["tactics_retry"].render(problem=problem)


def system_prompt(team_name: str, objective: str, scenario: str, graph: str, *, update: bool) -> str:
    return PROMPTS["tactics_system"].render(
        team_name=team_name,
        objective=objective,
        scenario=scenario,
        causal_graph=graph,
        examples=PROMPTS["tactics_examples"].render() if update else "",
    )


async def initial(
    llm: Chat | None,
    *,
    team_name: str,
    players: list[str],
    objective: str,
    scenario: str,
    graph: str,
    attempts: int = 3,
    max_items: int = 6,
    deadline: Whistle | None = None,
) -> Asked[str]:
    messages = [
        {"role": "system", "content": system_prompt(team_name, objective, scenario, graph, update=False)},
        {"role": "user", "content": PROMPTS["tactics_initial"].render(players=", ".join(players))},
    ]
    return await ask(
        llm,
        messages,
        role=ROLE,
        parse=lambda a: extract_tactics(a.text, max_items=max_items),
        attempts=attempts,
        retry=_retry,
        deadline=deadline,
    )


async def update(
    llm: Chat | None,
    *,
    team_name: str,
    players: list[str],
    objective: str,
    scenario: str,
    graph: str,
    chat_log: str,
    nearby_blocks: str,
    inventories: str,
    previous: str,
    opponent: str,
    attempts: int = 3,
    max_items: int = 6,
    deadline: Whistle | None = None,
) -> Asked[str]:
    messages = [
        {"role": "system", "content": system_prompt(team_name, objective, scenario, graph, update=True)},
        {
            "role": "user",
            "content": PROMPTS["tactics_update"].render(
                players=", ".join(players),
                chat_log=chat_log,
                nearby_blocks=nearby_blocks,
                inventories=inventories,
                opponent_tactics=opponent,
                previous_tactics=previous,
            ),
        },
    ]
    return await ask(
        llm,
        messages,
        role=ROLE,
        parse=lambda a: extract_tactics(a.text, max_items=max_items),
        attempts=attempts,
        retry=_retry,
        deadline=deadline,
    )
