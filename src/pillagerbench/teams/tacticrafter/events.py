"""Events as TactiCrafter's modules see them.

Deduplication (reference §7.6, `agents.context.compress_chat`): for each agent speaker, a block of
chat messages repeated back to back is kept once; the server's and judges' lines are kept. Every
event list that goes into a prompt or into memory goes through `dedupe`, which also counts what
it removed (`DedupStats`, recorded per player and episode).

A digest is a player's deduplicated events kept small for memory and checkpoints: each chat,
error or save event keeps its message and the player's inventory at that moment; observe events
keep everything, but only the last few are kept whole (the others keep their inventory).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from pillagerbench.agents import context as C
from pillagerbench.players.observation import Observation, is_whole, observation
from pillagerbench.scenarios import Scenario, Side


@dataclass
class DedupStats:
    before: int = 0
    after: int = 0
    chat_before: int = 0
    chat_after: int = 0

    def add(self, other: DedupStats) -> DedupStats:
        return DedupStats(
            self.before + other.before,
            self.after + other.after,
            self.chat_before + other.chat_before,
            self.chat_after + other.chat_after,
        )

    @property
    def reduction(self) -> float:
        """Share of events removed (0.28 = 28 % fewer events)."""
        return 0.0 if not self.before else round(1 - self.after / self.before, 4)

    def to_dict(self) -> dict:
        return {
            "events_before": self.before,
            "events_after": self.after,
            "chat_before": self.chat_before,
            "chat_after": self.chat_after,
            "reduction": self.reduction,
        }


def agent_names(scenario: Scenario) -> list[str]:
    """Speakers whose repeats are compressed: every team player (not the scenario's servers)."""
    return [p.name for s in scenario.sides for p in s.players]


def _chats(events: Sequence[list]) -> int:
    return sum(1 for e in events if e and e[0] == "onChat")


def dedupe(events: Sequence[list], agents: Iterable[str]) -> tuple[list[list], DedupStats]:
    out = C.compress_chat(list(events), agents)
    return out, DedupStats(len(events), len(out), _chats(events), _chats(out))


def digest(events: Sequence[list], *, keep_observe: int = 3, max_events: int = 600) -> list[list]:
    """Compact copy of (already deduplicated) events for memory: see the module docstring."""
    observe_at = [i for i, e in enumerate(events) if e and e[0] == "observe"][-keep_observe:]
    out = []
    for i, e in enumerate(events):
        if not e or len(e) < 2 or not isinstance(e[1], Mapping):
            continue
        kind, data = e[0], e[1]
        if kind == "observe" and i in observe_at:
            out.append([kind, dict(data)])
        else:
            small: dict[str, Any] = {"inventory": dict(data.get("inventory") or {})}
            if kind != "observe":
                small[kind] = data.get(kind)
            out.append([kind, small])
    if len(out) > max_events:  # keep the end of the episode (and every kept observe)
        out = out[-max_events:]
    return out


def digest_episode(
    events: Mapping[str, Sequence[list]], players: Sequence[str], agents: Iterable[str]
) -> tuple[dict[str, list[list]], dict[str, Any]]:
    """Each player's events deduplicated and digested for memory, and the deduplication counts
    (per player and `total`) for the record."""
    agents = list(agents)
    total = DedupStats()
    digests: dict[str, list[list]] = {}
    counts: dict[str, Any] = {}
    for name in players:
        deduped, stats = dedupe(events.get(name, []), agents)
        total = total.add(stats)
        counts[name] = stats.to_dict()
        digests[name] = digest(deduped)
    counts["total"] = total.to_dict()
    return digests, counts


def last_observation(events: Sequence[list]) -> Observation:
    """The last whole observation (a digest keeps only the last few whole)."""
    for e in reversed(events):
        if e and e[0] == "observe" and isinstance(e[1], Mapping) and is_whole(obs := observation(dict(e[1]))):
            return obs
    return C.last_observation(list(events)) if events else {}


def chat_lines(events: Sequence[list]) -> list[str]:
    return [str(e[1].get("onChat")) for e in events if e and e[0] == "onChat"]


def longest_chat(digests: Mapping[str, Sequence[list]]) -> list[str]:
    """The chat log of the team member who heard the most (paper: the longest event log)."""
    logs = [chat_lines(evs) for evs in digests.values()]
    return max(logs, key=len) if logs else []


def tail(lines: list[str], max_lines: int) -> str:
    if len(lines) > max_lines:
        lines = [f"... ({len(lines) - max_lines} earlier lines left out)"] + lines[-max_lines:]
    return "\n".join(lines) or C.NONE


def _speaker(line: str) -> str | None:
    if line.startswith("<") and ">" in line:
        return line[1 : line.index(">")]
    return None


def own_chat_with_inventory(digests: Mapping[str, Sequence[list]], *, max_lines: int = 60) -> str:
    """For every team member, each message they sent and their inventory at that moment
    (`Name: Chat: ...; Inventory: {...}`), the causal model's evidence."""
    parts = []
    for name, evs in digests.items():
        lines = []
        for e in evs:
            if e and e[0] == "onChat":
                line = str(e[1].get("onChat"))
                if _speaker(line) == name:
                    inv = e[1].get("inventory") or {}
                    lines.append(f"Chat: {line[len(name) + 3 :]}; Inventory: {dict(sorted(inv.items()))}")
        if len(lines) > max_lines:
            lines = lines[-max_lines:]
        parts.append(f"{name}:\n" + ("\n".join(lines) if lines else "(said nothing)"))
    return "\n".join(parts)


def opponent_speakers(scenario: Scenario, opponent: Side) -> set[str]:
    """The opponent's players and the scenario players that belong to it (its server in Dash & Dine)."""
    names = set(opponent.player_names)
    for p in scenario.extra_players:
        if p.name.lower().startswith(opponent.key.lower()):
            names.add(p.name)
    return names


def opponent_chat(
    digests: Mapping[str, Sequence[list]],
    scenario: Scenario,
    opponent: Side,
    *,
    max_lines: int = 60,
    world_chat: Sequence[str] | None = None,
) -> str:
    """What the opponent team said (and the game said about it), as heard by our players, or as the
    server logged it (`world_chat`, the match's chat log) when our players heard less (their bots
    only hear chat while they run code)."""
    speakers = opponent_speakers(scenario, opponent)
    # the game master names a side as upstream's did: "Team 1 is clean!", "... for team_blue"
    index = [s.key for s in scenario.sides].index(opponent.key)
    about = (
        opponent.team_name.lower(),
        f"team {opponent.key.lower()}",
        f"team_{opponent.key.lower()}",
        f"team {index} ",
    )
    heard = longest_chat(digests)
    if world_chat and len(world_chat) > len(heard):
        heard = list(world_chat)
    out = []
    for line in heard:
        who = _speaker(line)
        if who in speakers or (who is None and any(a in line.lower() for a in about)):
            out.append(line)
    return tail(out, max_lines)


def inventories_text(digests: Mapping[str, Sequence[list]]) -> str:
    lines = []
    for name, evs in digests.items():
        obs = last_observation(evs)
        used = (obs.get("status") or {}).get("inventoryUsed")
        used_txt = f" ({used}/36 slots used)" if used is not None else ""
        lines.append(f"{name}{used_txt}: {C.inventory_text(obs)}")
    return "\n".join(lines) or C.NONE


def nearby_blocks_text(digests: Mapping[str, Sequence[list]]) -> str:
    return "\n".join(f"{name}: {C.nearby_blocks(last_observation(evs))}" for name, evs in digests.items()) or C.NONE
