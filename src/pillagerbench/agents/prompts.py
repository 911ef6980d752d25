"""Prompt templates: plain text files next to a team's code, with named `$placeholders`.

    SYSTEM = PromptTemplate.load(Path(__file__).parent / "system.txt")
    SYSTEM.placeholders                      # {"primitives", "players"}
    text = SYSTEM.render(primitives=..., players=...)

Syntax is `string.Template`: `$name` or `${name}`; write `$$` for a literal dollar sign (JavaScript
template literals in a prompt: `$${x}`). Rendering checks both ways: a missing value or a value
the template does not use raises `PromptError`, so a renamed placeholder cannot go unnoticed.
Values are inserted as they are (a value containing `$` is not expanded again).
"""

from __future__ import annotations

import string
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path


class PromptError(ValueError):
    pass


@dataclass(frozen=True)
class PromptTemplate:
    text: str
    name: str = "<prompt>"

    @classmethod
    def load(cls, path: str | Path) -> PromptTemplate:
        path = Path(path)
        tpl = cls(path.read_text(encoding="utf-8"), path.name)
        _ = tpl.placeholders  # validate early: a bad `$` fails at load time
        return tpl

    @property
    def placeholders(self) -> frozenset[str]:
        names = set()
        for m in string.Template.pattern.finditer(self.text):
            if m.group("invalid") is not None:
                line = self.text.count("\n", 0, m.start()) + 1
                raise PromptError(f"{self.name}: a lone `$` at line {line} (write `$$` for a dollar sign)")
            name = m.group("named") or m.group("braced")
            if name:
                names.add(name)
        return frozenset(names)

    def render(self, given: Mapping[str, object] | None = None, /, **kw: object) -> str:
        values = {**(given or {}), **kw}
        needed = self.placeholders
        missing = sorted(needed - values.keys())
        extra = sorted(values.keys() - needed)
        if missing or extra:
            parts = []
            if missing:
                parts.append(f"missing values for {', '.join(missing)}")
            if extra:
                parts.append(f"values the template does not use: {', '.join(extra)}")
            raise PromptError(f"{self.name}: {'; '.join(parts)}")
        return string.Template(self.text).substitute({k: _text(v) for k, v in values.items()})


def _text(value: object) -> str:
    return value if isinstance(value, str) else str(value)


def load_prompts(directory: str | Path, suffix: str = ".txt") -> dict[str, PromptTemplate]:
    """Every prompt file of a folder by stem: {"system": PromptTemplate, ...}."""
    return {p.stem: PromptTemplate.load(p) for p in sorted(Path(directory).glob(f"*{suffix}"))}
