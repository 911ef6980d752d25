"""The entrant: the unit every table, rating and comparison speaks of (issues 37 and 53, docs/experiments.md).

An entrant is a team with its model for each role and the options that change its play; its label and
id are derived from those three, never stored apart from them:

    Entrant(team="tacticrafter", models={"team": "gpt-4o"}, options={"causal": False})
    .label == "tacticrafter@gpt-4o(no causal)", .id == 12 hex digits

- `team`: the side's team name (`red.name`);
- `models`: the team's model under "team" and each role whose own model differs; {} for a team
  without an LLM;
- `options`: the team's options that change play and differ from its defaults (teams/entrant.py
  computes them from a run's config);
- `label`: readable, `team@model(option, ...)`; a built-in team with its defaults is its name; a team
  played by an agent from outside is named by the agent (`agent:NAME/VERSION@model`, IDENTITY);
- `id`: the first 12 hex digits of the sha256 of the canonical {team, models, options}: the same
  entrant gives the same id in every process and on every machine. Two entrants are equal when their
  ids are, and hash as their id.

On disk (an episode record's `red_entrant`/`blue_entrant`) an entrant is `to_dict()`:
{"label", "id", "team", "models", "options"}; `from_dict` reads it back (the label and id are derived
again: the same rules give the same ones).
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

from pillagerbench.config.people import HUMAN_TEAM

# how a switch (a true/false option) reads in a label; any other option reads `key=value`
WORDS: dict[tuple[str, bool], str] = {
    ("causal", False): "no causal",
    ("opponent", False): "no opponent",
    ("update_tactics", False): "fixed tactics",
}

# a team played by an agent from outside (teams/tools/agent.py): it is named by the agent's declared name and
# version, and its model when given (options: name, version, model), not by the team's own name
IDENTITY: dict[str, tuple[str, str, str]] = {"agent": ("agent", "agent_version", "agent_model")}

# the people playing some of a team's players (docs/people.md): the option holding their names, in the order of
# the side's players; a person is the entrant `human:NAME`, a mixed team `cot@gpt-4o+human:NAME`
PEOPLE = "people"

LONG = 24  # a string value longer than this reads as `key=#` and 6 hex digits of its hash


def canonical(value: Any) -> Any:
    """Numbers as JSON would compare them (2.0 and 2 are one value), mappings with sorted keys."""
    if isinstance(value, float) and value.is_integer():
        return int(value)
    if isinstance(value, dict):
        return {str(k): canonical(v) for k, v in sorted(value.items())}
    if isinstance(value, (list, tuple)):
        return [canonical(v) for v in value]
    return value


def digest(value: Any, n: int) -> str:
    """The first `n` hex digits of the sha256 of `value` as canonical JSON."""
    text = json.dumps(value, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:n]


def _word(key: str, value: Any) -> str:
    if isinstance(value, bool) and (key, value) in WORDS:
        return WORDS[(key, value)]
    text = value if isinstance(value, str) else json.dumps(value, sort_keys=True, separators=(",", ":"))
    return f"{key}=#{digest(value, 6)}" if len(text) > LONG else f"{key}={text}"


def label_of(team: str, models: dict[str, str], options: dict[str, Any]) -> str:
    """`team@model(role=model, option, ...)`; a team without an LLM or options is its name."""
    words = [f"{role}={m}" for role, m in models.items() if role != "team"]
    words += [_word(k, v) for k, v in options.items()]
    at = f"@{models['team']}" if models else ""
    return f"{team}{at}" + (f"({', '.join(words)})" if words else "")


@dataclass(frozen=True, eq=False)
class Entrant:
    """One entrant (see the module): its maps are read, never changed (the id is computed once)."""

    team: str
    models: dict[str, str] = field(default_factory=dict)
    options: dict[str, Any] = field(default_factory=dict)

    @cached_property
    def id(self) -> str:
        return digest({"team": self.team, "models": self.models, "options": self.options}, 12)

    @cached_property
    def label(self) -> str:
        people = [f"human:{name}" for name in self.options.get(PEOPLE) or []]
        if people:
            rest = Entrant(self.team, self.models, {k: v for k, v in self.options.items() if k != PEOPLE})
            return "+".join(people if self.team == HUMAN_TEAM else [rest.label, *people])
        if self.team not in IDENTITY:
            return label_of(self.team, self.models, self.options)
        name_key, version_key, _ = IDENTITY[self.team]
        shown = f"{self.team}:{self.options.get(name_key, 'unknown')}/{self.options.get(version_key, '0')}"
        words = {k: v for k, v in self.options.items() if k not in (name_key, version_key)}
        return label_of(shown, self.models, words)

    def __hash__(self) -> int:
        return hash(self.id)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Entrant) and self.id == other.id

    def __repr__(self) -> str:
        return f"Entrant({self.label!r}, id={self.id})"

    def with_people(self, names: list[str]) -> Entrant:
        """This entrant with people playing some of its players (their names, as they typed them)."""
        return Entrant(self.team, self.models, {**self.options, PEOPLE: list(names)}) if names else self

    def to_dict(self) -> dict[str, Any]:
        """As an episode record holds it: label, id, team, models, options."""
        return {
            "label": self.label,
            "id": self.id,
            "team": self.team,
            "models": dict(self.models),
            "options": dict(self.options),
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Entrant:
        """An entrant as a record holds it (its label and id derived again from team, models and options)."""
        return cls(str(data["team"]), dict(data.get("models") or {}), dict(data.get("options") or {}))
