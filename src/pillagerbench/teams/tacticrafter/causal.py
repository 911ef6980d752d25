"""The causal model (paper §Causal Model): a graph of actions, what each needs (causes) and what
it yields (effects).

- First episode: an initial graph from the primitives' documentation and the scenario, as JSON,
  with at least one relation per primitive module (`initial`).
- Later episodes: new or corrected relations inferred from what each team member said in chat and
  held at that moment, merged into the graph (`update`; a relation with the same action replaces
  the old one).
- Rendered for other prompts as `Action: <call>; Cause: [...]; Effect [...]` lines; that text can
  be parsed back (`CausalGraph.parse_text`).

Accepted JSON shapes: a list of `[action, [causes], [effects]]`, a list of
`{"action", "causes"/"cause", "effects"/"effect"}` objects, or `{action: [[causes], [effects]]}`;
optionally wrapped as `{"relations": ...}`. Anything else is a ValueError with the reason (which
is shown to the model when it is asked again).
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

from pillagerbench.agents.asking import Asked, Chat, Whistle, ask
from pillagerbench.llm import LLMResponse
from pillagerbench.llm.parsing import parse_json
from pillagerbench.players import primitives as prim
from pillagerbench.scenarios import Scenario

from .templates import PROMPTS

ROLE = "causal"


@dataclass(frozen=True)
class Relation:
    action: str
    causes: tuple[str, ...] = ()
    effects: tuple[str, ...] = ()

    def render(self) -> str:
        return f"Action: {self.action}; Cause: {list(self.causes)}; Effect {list(self.effects)}"

    def to_list(self) -> list:
        return [self.action, list(self.causes), list(self.effects)]


def _names(value: Any, what: str, action: str) -> tuple[str, ...]:
    if value is None:
        return ()
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, (list, tuple)) or not all(isinstance(v, (str, int, float)) for v in value):
        raise ValueError(f"the {what} of {action!r} must be a list of item names")
    return tuple(str(v).strip() for v in value if str(v).strip())


def parse_relations(value: object) -> list[Relation]:
    """Relations from a JSON value (see the module docstring for the shapes)."""
    if isinstance(value, dict) and "relations" in value:
        value = value["relations"]
    items: list[tuple[Any, Any, Any]] = []
    if isinstance(value, dict):
        for action, ce in value.items():
            if not isinstance(ce, (list, tuple)) or len(ce) != 2:
                raise ValueError(f"the value of {action!r} must be [[causes], [effects]]")
            items.append((action, ce[0], ce[1]))
    elif isinstance(value, list):
        for n, rel in enumerate(value):
            if isinstance(rel, dict):
                action = rel.get("action")
                items.append((action, rel.get("causes", rel.get("cause")), rel.get("effects", rel.get("effect"))))
            elif isinstance(rel, (list, tuple)) and len(rel) == 3:
                items.append(tuple(rel))
            else:
                raise ValueError(f"relation {n + 1} is neither [action, [causes], [effects]] nor an object")
    else:
        raise ValueError("the graph must be a JSON list of [action, [causes], [effects]] relations")
    out = []
    for action, causes, effects in items:
        if not isinstance(action, str) or not action.strip():
            raise ValueError("every relation needs an action (a function call as text)")
        action = action.strip()
        out.append(Relation(action, _names(causes, "causes", action), _names(effects, "effects", action)))
    return out


_LINE = re.compile(r"^Action:\s*(.*?);\s*Cause:\s*(\[.*?\]);\s*Effect:?\s*(\[.*\])\s*$")


def _list_text(text: str) -> tuple[str, ...]:
    return tuple(m.group(1) or m.group(2) for m in re.finditer(r"'([^']*)'|\"([^\"]*)\"", text))


@dataclass
class CausalGraph:
    relations: list[Relation] = field(default_factory=list)

    def __len__(self) -> int:
        return len(self.relations)

    def render(self) -> str:
        return "\n".join(r.render() for r in self.relations)

    def text(self) -> str:
        """For prompts: the rendered graph, or a note that there is none."""
        return self.render() or "(no causal graph)"

    def merge(self, new: Iterable[Relation]) -> dict[str, int]:
        """Add new relations; one with an action already in the graph replaces it."""
        index = {r.action: i for i, r in enumerate(self.relations)}
        added = changed = 0
        for rel in new:
            if rel.action in index:
                if self.relations[index[rel.action]] != rel:
                    self.relations[index[rel.action]] = rel
                    changed += 1
            else:
                index[rel.action] = len(self.relations)
                self.relations.append(rel)
                added += 1
        return {"added": added, "changed": changed, "total": len(self.relations)}

    def to_json(self) -> list:
        return [r.to_list() for r in self.relations]

    @classmethod
    def from_json(cls, value: object) -> CausalGraph:
        return cls(parse_relations(value or []))

    @classmethod
    def parse_text(cls, text: str) -> CausalGraph:
        """Back from the rendered lines (lines that do not match are skipped)."""
        rels = []
        for line in text.splitlines():
            m = _LINE.match(line.strip())
            if m:
                rels.append(Relation(m.group(1).strip(), _list_text(m.group(2)), _list_text(m.group(3))))
        return cls(rels)

    def missing_modules(self, modules: Sequence[str]) -> list[str]:
        """Primitive modules none of whose functions appears in any action."""
        calls = {m.group(1) for r in self.relations for m in re.finditer(r"([A-Za-z_]\w*)\s*\(", r.action)}
        return [m for m in modules if m in prim.MODULES and not calls & set(prim.MODULES[m])]


def complete_items(text: str) -> list:
    """The complete elements at the start of a JSON list that was cut off (a truncated answer):
    `[[a], [b], [c` gives `[[a], [b]]`."""
    start = text.find("[")
    if start < 0:
        return []
    decoder, i = json.JSONDecoder(), start + 1
    items: list[Any] = []
    while True:
        while i < len(text) and text[i] in " \t\r\n,":
            i += 1
        try:
            value, i = decoder.raw_decode(text, i)
        except ValueError:
            return items
        items.append(value)


def _parse_answer(answer: Any, allow_empty: bool = False) -> list[Relation]:
    try:
        try:
            value = parse_json(answer.text)
        except ValueError as exc:
            raise ValueError(f"no valid JSON in the answer ({exc})") from None
        rels = parse_relations(value)
    except ValueError:
        salvaged = complete_items(answer.text) if getattr(answer, "truncated", False) else []
        if not salvaged:
            raise
        rels = parse_relations(salvaged)  # the relations written before the token limit cut the answer
    if not rels and not allow_empty:
        raise ValueError("the graph is empty")
    return rels


def _retry(problem: str) -> str:
    return PROMPTS["causal_retry"].render(problem=problem)


async def initial(
    llm: Chat | None, scenario: Scenario, *, attempts: int = 3, deadline: Whistle | None = None
) -> tuple[CausalGraph | None, Asked[CausalGraph]]:
    """The first graph, from the primitives' documentation and the scenario (one-shot)."""
    modules = list(scenario.primitives)
    prompt = PROMPTS["causal_initial"].render(
        primitives=prim.docs(modules), scenario=scenario.description(), modules=", ".join(modules)
    )

    def parse(answer: LLMResponse) -> CausalGraph:
        graph = CausalGraph(_parse_answer(answer))
        missing = graph.missing_modules(modules)
        if missing:
            raise ValueError(
                f"no relation uses the functions of: {', '.join(missing)} "
                "(give at least one relation per control function group)"
            )
        return graph

    asked = await ask(
        llm,
        [{"role": "user", "content": prompt}],
        role=ROLE,
        parse=parse,
        attempts=attempts,
        retry=_retry,
        deadline=deadline,
    )
    if asked.value is None:  # keep the best partial graph if one parsed at all
        for entry in reversed(asked.attempts):
            if "answer" in entry:
                try:
                    return CausalGraph(
                        _parse_answer(_Text(entry["answer"], entry.get("finish_reason") == "length"))
                    ), asked
                except ValueError:
                    continue
    return asked.value, asked


async def update(
    llm: Chat | None,
    scenario: Scenario,
    graph: CausalGraph,
    evidence: str,
    *,
    attempts: int = 3,
    deadline: Whistle | None = None,
) -> tuple[list[Relation] | None, Asked[list[Relation]]]:
    """New relations from last episode's evidence (few-shot); the caller merges them."""
    modules = list(scenario.primitives)
    prompt = PROMPTS["causal_update"].render(
        primitives=prim.docs(modules), scenario=scenario.description(), graph=graph.text(), evidence=evidence
    )
    asked = await ask(
        llm,
        [{"role": "user", "content": prompt}],
        role=ROLE,
        parse=lambda a: _parse_answer(a, allow_empty=True),
        attempts=attempts,
        retry=_retry,
        deadline=deadline,
    )
    return asked.value, asked


@dataclass
class _Text:
    text: str
    truncated: bool = False
