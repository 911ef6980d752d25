"""The control primitives' documentation for LLM prompts (the "context" upstream showed to LLMs).

Each primitive module lives in `js/bot/primitives/<name>.js` with its documentation in
`<name>.md` next to it; `mineflayer.md` documents the bot API subset agent code may use. The modules and
their functions are listed once, in `js/bot/primitives/modules.json` (read here and by `index.js`).
"""

from __future__ import annotations

import json

from pillagerbench.host.node import JS_DIR

PRIMITIVES_DIR = JS_DIR / "bot" / "primitives"

# module -> functions it defines (what `Player(primitives=[...])` accepts, besides module names), declared
# once on the JavaScript side: `js/bot/primitives/modules.json`, which `index.js` builds the primitives from
MODULES: dict[str, list[str]] = json.loads((PRIMITIVES_DIR / "modules.json").read_text(encoding="utf-8"))
DOC_ONLY = ("mineflayer",)


def doc(name: str) -> str:
    """The documentation text of one primitive module (or `mineflayer` for the bot API)."""
    if name not in MODULES and name not in DOC_ONLY:
        raise KeyError(f"unknown primitive module {name!r} (valid: {', '.join([*MODULES, *DOC_ONLY])})")
    return (PRIMITIVES_DIR / f"{name}.md").read_text(encoding="utf-8").strip()


def docs(names: list[str] | None = None) -> str:
    """The documentation of several modules joined for a prompt (default: all, then the bot API)."""
    names = list(names) if names is not None else [*MODULES, *DOC_ONLY]
    return "\n\n".join(doc(n) for n in names)


def functions(names: list[str] | None = None) -> list[str]:
    """Function names available with `Player(primitives=names)`."""
    if names is None:
        return [f for fs in MODULES.values() for f in fs]
    out: list[str] = []
    for n in names:
        if n in MODULES:
            out += MODULES[n]
        elif n not in DOC_ONLY:
            out.append(n)
    return out
