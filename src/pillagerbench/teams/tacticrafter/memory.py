"""What TactiCrafter remembers between the episodes of a series, and its files.

Each episode writes to the team's directory (`<run>/episode_XXX/<side>/`):

- `tactics.json`: `{"tactics", "previous_tactics", "source", "episode"}`
- `opponent_tactics.json`: `{"opponent_tactics", "source", "episode"}`
- `causal_graph.json`: `{"relations": [[action, [causes], [effects]], ...], "text": "Action: ...", "episode"}`
- `code.json`: per player `{"code", "critique", "success", "iterations", "events"}`: the last
  good code, the last critique, and the player's deduplicated event digest of the episode.

A checkpoint directory holds the same four files plus `team.json` (the whole memory, the format
every team's checkpoint has). `Memory.read(directory)` accepts either: `team.json` if present,
else the four files (so an episode's team directory is itself a checkpoint).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pillagerbench.rundir import team_state_path

from .causal import CausalGraph
from .opponent import UNKNOWN

FILES = ("tactics.json", "opponent_tactics.json", "causal_graph.json", "code.json")


@dataclass
class Memory:
    tactics: str | None = None
    previous_tactics: str | None = None
    tactics_source: str | None = None  # generated | updated | preset | kept | none
    opponent_tactics: str = UNKNOWN
    opponent_source: str | None = None
    graph: CausalGraph = field(default_factory=CausalGraph)
    code: dict[str, dict[str, Any]] = field(default_factory=dict)  # player -> code/critique/success/...
    events: dict[str, list] = field(default_factory=dict)  # player -> last episode's digest
    episodes: int = 0  # episodes played with this memory

    # --- as one dict (team.json) -------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        return {
            "tactics": self.tactics,
            "previous_tactics": self.previous_tactics,
            "tactics_source": self.tactics_source,
            "opponent_tactics": self.opponent_tactics,
            "opponent_source": self.opponent_source,
            "causal_graph": self.graph.to_json(),
            "code": self.code,
            "events": self.events,
            "episodes": self.episodes,
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Memory:
        return cls(
            tactics=d.get("tactics"),
            previous_tactics=d.get("previous_tactics"),
            tactics_source=d.get("tactics_source"),
            opponent_tactics=d.get("opponent_tactics") or UNKNOWN,
            opponent_source=d.get("opponent_source"),
            graph=CausalGraph.from_json(d.get("causal_graph")),
            code={k: dict(v) for k, v in (d.get("code") or {}).items()},
            events={k: list(v) for k, v in (d.get("events") or {}).items()},
            episodes=int(d.get("episodes") or 0),
        )

    # --- as files -----------------------------------------------------------------------------
    def write(self, directory: Path, episode: int | None = None, iterations: dict[str, int] | None = None) -> None:
        directory = Path(directory)
        directory.mkdir(parents=True, exist_ok=True)
        _dump(
            directory / "tactics.json",
            {
                "tactics": self.tactics,
                "previous_tactics": self.previous_tactics,
                "source": self.tactics_source,
                "episode": episode,
            },
        )
        _dump(
            directory / "opponent_tactics.json",
            {"opponent_tactics": self.opponent_tactics, "source": self.opponent_source, "episode": episode},
        )
        _dump(
            directory / "causal_graph.json",
            {"relations": self.graph.to_json(), "text": self.graph.render(), "episode": episode},
        )
        players = sorted(set(self.code) | set(self.events))
        _dump(
            directory / "code.json",
            {
                name: {
                    **self.code.get(name, {}),
                    **({"iterations": iterations[name]} if iterations and name in iterations else {}),
                    "events": self.events.get(name, []),
                }
                for name in players
            },
        )

    @classmethod
    def read(cls, directory: Path) -> Memory:
        directory = Path(directory)
        team = team_state_path(directory)
        if team.exists():
            data = json.loads(team.read_text())
            return cls.from_dict(data.get("state", data))  # a checkpoint of an early version: the memory alone
        if not any((directory / f).exists() for f in FILES):
            raise FileNotFoundError(f"{directory} holds no TactiCrafter checkpoint (team.json or {', '.join(FILES)})")
        mem = cls()
        if (p := directory / "tactics.json").exists():
            d = json.loads(p.read_text())
            mem.tactics, mem.previous_tactics = d.get("tactics"), d.get("previous_tactics")
            mem.tactics_source = d.get("source")
        if (p := directory / "opponent_tactics.json").exists():
            d = json.loads(p.read_text())
            mem.opponent_tactics = d.get("opponent_tactics") or UNKNOWN
            mem.opponent_source = d.get("source")
        if (p := directory / "causal_graph.json").exists():
            d = json.loads(p.read_text())
            if isinstance(d, str):  # the rendered text only
                mem.graph = CausalGraph.parse_text(d)
            elif isinstance(d, dict) and d.get("relations") is not None:
                mem.graph = CausalGraph.from_json(d["relations"])
            elif isinstance(d, dict):
                mem.graph = CausalGraph.parse_text(d.get("text") or "")
            else:
                mem.graph = CausalGraph.from_json(d)
        if (p := directory / "code.json").exists():
            for name, entry in json.loads(p.read_text()).items():
                entry = dict(entry)
                mem.events[name] = list(entry.pop("events", []) or [])
                entry.pop("iterations", None)
                mem.code[name] = entry
        mem.episodes = 1 if mem.tactics or mem.code else 0
        return mem


def _dump(path: Path, value: Any) -> None:
    tmp = path.with_suffix(path.suffix + ".tmp")
    tmp.write_text(json.dumps(value, indent=1, default=str))
    tmp.replace(path)
