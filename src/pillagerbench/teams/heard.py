"""What a team's people said (docs/people.md, "A person's teammate hears the person"): the chat lines
spoken by the players of a side that people play (`TeamContext.people`), for the prompt of an agent
playing beside them. A line is chat as the match logs it, `<player> message` (chat.txt, and a bot's
`onChat` events); the game's own lines name no player and are never a person's.

    said_by(ctx.last_episode.get("chat") or [], ctx.people)    # ["<Ryn> take the left side", ...]

With no people on the side nothing is ever said, so an agents-only team's prompt is as it was."""

from __future__ import annotations

import re
from collections.abc import Iterable

from pillagerbench.agents.prompts import PromptTemplate

_LINE = re.compile(r"^<(\w+)> ")


def said_by(lines: Iterable[str], people: Iterable[str], *, max_lines: int | None = None) -> list[str]:
    """The lines of `lines` spoken by one of `people`, in their order (the last `max_lines` of them)."""
    who = set(people)
    if not who:
        return []
    said = [line for line in lines if (m := _LINE.match(line)) and m.group(1) in who]
    if max_lines is None:
        return said
    return said[-max_lines:] if max_lines > 0 else []


def people_said(section: PromptTemplate, lines: Iterable[str], people: tuple[str, ...], *, max_lines: int) -> str:
    """A prompt's section of what the side's `people` said among `lines` (`section` rendered with `people` and
    `said`), or '' when none of them spoke."""
    said = said_by(lines, people, max_lines=max_lines)
    return section.render(people=", ".join(people), said="\n".join(said)) if said else ""
