"""Helpers for event lists in upstream's shape: `[[type, data], ...]` ending with `["observe", data]`.

Types: onChat, onError, onSave, observe. Every event's data holds the state keys (voxels, status,
inventory, nearbyChests, blockRecords); on* events add their own key with the message.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from .observation import Observation, observation

EVENT_TYPES = ("onChat", "onError", "onSave", "observe")
STATE_KEYS = ("voxels", "status", "inventory", "nearbyChests", "blockRecords")
_CHAT_LINE = re.compile(r"^<([^>]+)> (.*)$", re.S)


def messages(events: Iterable[list], kind: str) -> list:
    """The `kind` values of the events of that type (e.g. every chat line)."""
    return [e[1].get(kind) for e in events if e and e[0] == kind]


def chat_log(events: Iterable[list]) -> list[str]:
    """Chat lines, "<name> message" for players and the plain text for the server."""
    return messages(events, "onChat")


def chats_by(events: Iterable[list], username: str) -> list[str]:
    """What `username` said (without the "<name> " prefix)."""
    out = []
    for line in chat_log(events):
        m = _CHAT_LINE.match(line or "")
        if m and m.group(1) == username:
            out.append(m.group(2))
    return out


def errors(events: Iterable[list]) -> list[str]:
    return messages(events, "onError")


def saves(events: Iterable[list]) -> list[str]:
    return messages(events, "onSave")


def last_observation(events: list) -> Observation:
    """The data of the final observe event (or of the last event with state)."""
    for e in reversed(events):
        if e and e[0] == "observe":
            return observation(e[1])
    return observation(events[-1][1]) if events else {}


def without_state(events: Iterable[list]) -> list[list]:
    """Events with only their own key (for compact logs): [type, message] and the final observe."""
    out = []
    for e in events:
        if e[0] == "observe":
            out.append(e)
        else:
            out.append([e[0], e[1].get(e[0])])
    return out


def dedupe(events: Iterable[list]) -> list[list]:
    """Drop consecutive repeats of the same [type, message] (state ignored), keeping the last observe."""
    out: list[list] = []
    prev = None
    for e in events:
        key = (e[0], e[1].get(e[0]) if e[0] != "observe" else None)
        if e[0] != "observe" and key == prev:
            continue
        prev = key
        out.append(e)
    return out
