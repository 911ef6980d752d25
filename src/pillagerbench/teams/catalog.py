"""`pillagerbench teams`: every team a name can reach (registered, entry points), where it comes
from, the scenarios it plays, whether it uses an LLM, and its options with their defaults. Any
class `package.module:Class` that subclasses Team works too (docs/your-team.md)."""

from __future__ import annotations

import json

from pillagerbench.teams import available


def rows() -> list[dict]:
    return [
        {
            "team": e.name,
            "from": e.source,
            "scenarios": ", ".join(e.cls.scenarios) if e.cls.scenarios else "all",
            "llm": "yes" if e.cls.uses_llm else "no",
            "options": ", ".join(f"{k}={json.dumps(v)}" for k, v in e.options.items()) or "–",
        }
        for e in available()
    ]


def main(argv: list[str]) -> int:
    table = rows()
    widths = {k: max(len(k), *(len(r[k]) for r in table)) for k in table[0]}
    print("  ".join(k.ljust(w) for k, w in widths.items()).rstrip())
    for r in table:
        print("  ".join(r[k].ljust(w) for k, w in widths.items()).rstrip())
    print(
        "\nAlso: any package.module:Class subclassing pillagerbench.teams.Team (red=package.module:Class); "
        "options as red.KEY=VALUE. See docs/your-team.md."
    )
    return 0
