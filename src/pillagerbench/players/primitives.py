"""The control primitives' documentation for LLM prompts (the "context" upstream showed to LLMs).

Each primitive module lives in `js/bot/primitives/<name>.js` with its documentation in
`<name>.md` next to it; `mineflayer.md` documents the bot API subset agent code may use.
"""

from __future__ import annotations

from pillagerbench.node import JS_DIR

PRIMITIVES_DIR = JS_DIR / "bot" / "primitives"

# module -> functions it defines (what `Player(primitives=[...])` accepts, besides module names)
MODULES: dict[str, list[str]] = {
    "mineBlock": ["mineBlock", "blockExists"],
    "craftItem": ["craftItem"],
    "placeItem": ["placeItem"],
    "smeltItem": ["smeltItem"],
    "killMob": ["killMob"],
    "giveToPlayer": ["giveToPlayer", "goToPlayer", "discard"],
    "useChest": ["getItemFromChest", "depositItemIntoChest", "checkItemInsideChest"],
    "farm": [
        "tillLand",
        "plantCrop",
        "plantSweetBerryBushes",
        "plantWheatSeeds",
        "plantPotatoes",
        "plantCarrots",
        "plantBeetrootSeeds",
        "plantMelonSeeds",
        "plantPumpkinSeeds",
        "plantCocoaBeans",
        "plantSugarCane",
        "harvest",
        "harvestBerries",
        "harvestWheat",
        "harvestPotatoes",
        "harvestCarrots",
        "harvestBeetroot",
        "harvestCocoa",
        "harvestMelons",
        "harvestPumpkins",
        "harvestSugarCane",
        "equipBucket",
        "milkCow",
        "destroyCrop",
    ],
    "multiAgent": ["sendSignal", "waitSignal"],
    "exploreUntil": ["exploreUntil"],
}
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
