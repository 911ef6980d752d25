"""Observations and events as prompt text.

Events are upstream's `[type, data]` lists (see pillagerbench.players.events); an observation is
the data of an `observe` event. Every function returns plain text ready for a `$placeholder`,
with a readable stand-in ("none") when there is nothing to show.

    obs = last_observation(ctx.observations["Ryn"])
    nearby_blocks(obs), nearby_entities(obs), inventory_text(obs), status_text(obs)
    events = episode_events(ctx.last_episode, ["Ryn", "Raze"])    # {player: events} of last episode
    chat_log_text(events["Ryn"], agents=[...])                      # repeats of agents compressed
    errors_text(events["Ryn"])
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

from pillagerbench.players import events as ev
from pillagerbench.players.events import last_observation as last_observation  # re-exported for agents
from pillagerbench.players.observation import Observation
from pillagerbench.rundir.names import player_events_name

NONE = "none"


def _fmt(v: float) -> str:
    return f"{v:.1f}".rstrip("0").rstrip(".") if isinstance(v, float) else str(v)


def nearby_blocks(obs: Observation, *, records: bool = False) -> str:
    """Block names around the player (voxels; with `records`, also every block seen this run)."""
    names = set(obs.get("voxels") or [])
    if records:
        names |= set(obs.get("blockRecords") or [])
    return ", ".join(sorted(names)) or NONE


def nearby_entities(obs: Observation) -> str:
    """Mobs within 32 blocks, nearest first: "cow (3.2 blocks away), chicken (5 blocks away)"."""
    ents = (obs.get("status") or {}).get("entities") or {}
    return (
        ", ".join(f"{name} ({_fmt(float(d))} blocks away)" for name, d in sorted(ents.items(), key=lambda kv: kv[1]))
        or NONE
    )


def inventory_text(obs: Observation) -> str:
    inv = obs.get("inventory") or {}
    return ", ".join(f"{name}: {count}" for name, count in sorted(inv.items())) or "empty"


def position_text(obs: Observation) -> str:
    p = (obs.get("status") or {}).get("position")
    return f"x={_fmt(float(p['x']))}, y={_fmt(float(p['y']))}, z={_fmt(float(p['z']))}" if p else "unknown"


def status_text(obs: Observation) -> str:
    """Position, health, hunger, equipment and time of day, one per line."""
    s = obs.get("status") or {}
    lines = [f"Position: {position_text(obs)}"]
    if "health" in s:
        lines.append(f"Health: {_fmt(float(s['health']))}/20")
    if "food" in s:
        lines.append(f"Hunger: {_fmt(float(s['food']))}/20")
    if s.get("biome"):
        lines.append(f"Biome: {s['biome']}")
    if s.get("timeOfDay"):
        lines.append(f"Time: {s['timeOfDay']}")
    held = [e for e in (s.get("equipment") or []) if e]
    if held:
        lines.append(f"Equipment: {', '.join(held)}")
    return "\n".join(lines)


def chests_text(obs: Observation) -> str:
    """Chests seen nearby and what is known of their contents."""
    chests = obs.get("nearbyChests") or {}
    out = []
    for pos, content in sorted(chests.items()):
        if isinstance(content, dict):
            content = ", ".join(f"{k}: {v}" for k, v in sorted(content.items())) or "empty"
        elif content == "Unknown":
            content = "contents unknown"
        out.append(f"{pos}: {content}")
    return "\n".join(out) or NONE


def observation_text(obs: Observation) -> str:
    """Everything above in one block (for a prompt about a single player)."""
    return "\n".join(
        [
            status_text(obs),
            f"Inventory: {inventory_text(obs)}",
            f"Nearby blocks: {nearby_blocks(obs)}",
            f"Nearby entities: {nearby_entities(obs)}",
            f"Nearby chests: {chests_text(obs)}",
        ]
    )


# --- events of an episode ----------------------------------------------------------------------


def read_events(path: str | Path) -> list[list]:
    """One player's events from a JSONL file (missing file: no events; a torn last line is skipped)."""
    path = Path(path)
    if not path.exists():
        return []
    out = []
    for line in path.read_text(encoding="utf-8").splitlines():
        try:
            out.append(json.loads(line))
        except json.JSONDecodeError:
            continue
    return out


def episode_events(last_episode: Mapping[str, Any] | None, players: Iterable[str]) -> dict[str, list[list]]:
    """The events each player produced last episode (from `ctx.last_episode["events_dir"]`)."""
    directory = (last_episode or {}).get("events_dir")
    return {name: read_events(Path(directory) / player_events_name(name)) if directory else [] for name in players}


def _speaker(line: str) -> str | None:
    if line.startswith("<") and ">" in line:
        return line[1 : line.index(">")]
    return None


def compress_chat(events: Sequence[list], agents: Iterable[str]) -> list[list]:
    """Upstream's deduplication (reference §7.6): for each agent speaker, a block of messages that
    repeats back to back is kept once. Chat of others (the server, judges) and non-chat events are
    untouched; the order of what is kept is the original order."""
    agents = set(agents)
    by_speaker: dict[str, list[int]] = {}
    for i, e in enumerate(events):
        if e and e[0] == "onChat":
            who = _speaker(str(e[1].get("onChat", "")))
            if who in agents:
                by_speaker.setdefault(who, []).append(i)
    drop: set[int] = set()
    for idxs in by_speaker.values():
        msgs = [events[i][1].get("onChat") for i in idxs]
        n, i = len(msgs), 0
        while i < n:
            for length in range(1, (n - i) // 2 + 1):
                block = msgs[i : i + length]
                if block == msgs[i + length : i + 2 * length]:
                    copies = 2
                    while (
                        i + (copies + 1) * length <= n
                        and msgs[i + copies * length : i + (copies + 1) * length] == block
                    ):
                        copies += 1
                    drop.update(idxs[i + length : i + copies * length])
                    i += copies * length
                    break
            else:
                i += 1
    return [e for k, e in enumerate(events) if k not in drop]


def chat_lines(events: Sequence[list], agents: Iterable[str] = ()) -> list[str]:
    """The chat log with repeats compressed (agents: whose repeats to compress; default none)."""
    return ev.chat_log(compress_chat(events, agents))


def chat_log_text(events: Sequence[list], agents: Iterable[str] = (), *, max_lines: int = 80) -> str:
    """The chat log (last `max_lines` lines after compression) as text."""
    lines = [str(x) for x in chat_lines(events, agents)]
    if len(lines) > max_lines:
        lines = [f"... ({len(lines) - max_lines} earlier lines left out)"] + lines[-max_lines:]
    return "\n".join(lines) or NONE


def error_lines(events: Sequence[list]) -> list[str]:
    """Distinct error messages in order of first appearance."""
    seen: dict[str, None] = {}
    for msg in ev.errors(events):
        seen.setdefault(str(msg), None)
    return list(seen)


def errors_text(events: Sequence[list], *, max_errors: int = 10) -> str:
    errs = error_lines(events)
    more = len(errs) - max_errors
    errs = errs[:max_errors] + ([f"... and {more} more"] if more > 0 else [])
    return "\n".join(errs) or NONE
