"""What every scenario's layouts share: the `layout=` value (the paper's, a seed, or a file), the
splits of the seed space, a draw that is the same on every machine, and the reachability check.

A layout is the scenario's arena as data (docs/layouts.md). `layout=paper` is upstream's map;
`layout=SEED` a variant built by the scenario's generator; `layout=FILE.json` one written by hand
(or by `pillagerbench layout show ... --json`). Splits: `dev` seeds are for anyone to tune on; `test`
seeds are drawn fresh for every episode from a space too large to enumerate, so no team can have
been tuned to them.
"""

from __future__ import annotations

import json
import secrets
from collections import deque
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from random import Random
from typing import Any, Generic, Protocol, Self, TypeVar

from pydantic import ValidationError

from pillagerbench.config.compose import ConfigError
from pillagerbench.config.registry import Registry

PAPER = "paper"
DEV_SEEDS = range(1_000_000)  # for tuning, reporting and debugging: documented, public
TEST_SEEDS = range(1_000_000, 2**53)  # drawn fresh per episode; 2**53: exact in JSON and JavaScript
SPLITS: Registry[str] = Registry(  # the splits a run or league draws its layouts from, and what each is
    "split",
    {
        "paper": "the paper's map",
        "dev": "a dev seed drawn from the episode's seed (the same every time)",
        "test": "a fresh seed from the operating system",
    },
)

LayoutKey = str | int  # "paper", a seed, or a layout file's path


class Layout(Protocol):
    """What every scenario's layout model (a frozen pydantic model) is, seen from outside its scenario:
    its `layout=` key, built from a layout file's data, and its data as a layout file holds it."""

    @property
    def key(self) -> LayoutKey: ...

    @classmethod
    def model_validate(cls, obj: object) -> Self: ...

    def model_dump(self, *, mode: str = ...) -> dict[str, Any]: ...


LayoutT = TypeVar("LayoutT", bound=Layout)


class LayoutError(ConfigError):
    """A layout value, a layout file or a generated layout that is not valid; one line."""


def parse_layout(value: object) -> LayoutKey:
    """`layout=` as given: "paper", a seed (a non-negative integer below 2**53) or an existing .json file."""
    if isinstance(value, bool) or value is None:
        raise LayoutError(f"layout={value!r}: {ACCEPTED}")
    if isinstance(value, int) or (isinstance(value, str) and value.strip().lstrip("-").isdigit()):
        seed = int(value)
        if not 0 <= seed < TEST_SEEDS.stop:
            raise LayoutError(f"layout={seed}: a seed is an integer from 0 to {TEST_SEEDS.stop - 1}")
        return seed
    text = str(value)
    if text == PAPER:
        return PAPER
    if text.endswith(".json"):
        if not Path(text).is_file():
            raise LayoutError(f"layout={text}: no such layout file")
        return text
    raise LayoutError(f"layout={text!r}: {ACCEPTED}")


ACCEPTED = "valid: paper, a seed (an integer 0..2**53-1), or a layout file (.json)"


def split_of(key: LayoutKey) -> str:
    """The split a layout belongs to: paper, dev, test, or custom (a file)."""
    if key == PAPER:
        return "paper"
    if isinstance(key, int):
        return "dev" if key in DEV_SEEDS else "test"
    return "custom"


def parse_split(value: object) -> str | None:
    if value is None or (isinstance(value, str) and value in SPLITS):
        return value
    raise LayoutError(f"{SPLITS.unknown(value)} (or null: the layout= value)")


def episode_layout(layout: LayoutKey, split: str | None, seed: int) -> LayoutKey:
    """The layout an episode is played on. `split=dev`: a dev seed drawn from the episode's seed (the
    same every time); `split=test`: a fresh seed from the operating system; else `layout` itself."""
    if split == "dev":
        return DEV_SEEDS.start + int(Random(seed).random() * len(DEV_SEEDS))
    if split == "test":
        return TEST_SEEDS.start + secrets.randbelow(len(TEST_SEEDS))
    return PAPER if split == "paper" else layout


def read_layout_file(path: str) -> dict[str, Any]:
    try:
        data = json.loads(Path(path).read_text())
    except (OSError, ValueError) as exc:
        raise LayoutError(f"layout={path}: not a layout file ({exc})") from None
    if not isinstance(data, dict):
        raise LayoutError(f"layout={path}: not a layout file (a JSON object is expected)")
    return data


@dataclass(frozen=True)
class LayoutRules(Generic[LayoutT]):
    """A scenario's layouts: their model, the paper's, the generator and the validation."""

    scenario: str
    model: type[LayoutT]
    paper: LayoutT
    generate: Callable[[int], LayoutT]
    problems: Callable[[LayoutT], list[str]]

    def make(self, key: LayoutKey) -> LayoutT:
        """The layout of a `layout=` value (parse_layout's): the paper's, a seed's, or a file's (validated)."""
        if key == PAPER:
            return self.paper
        if isinstance(key, int):
            return self.generate(key)
        data = read_layout_file(key)
        if "scenario" not in data:
            raise LayoutError(
                f"layout={key}: not a layout file (it names no scenario; `pillagerbench layout show` writes one)"
            )
        if data.get("scenario") != self.scenario:
            raise LayoutError(f"layout={key}: a layout of {data.get('scenario')!r}, not of {self.scenario}")
        try:
            layout = self.model.model_validate({**data, "key": key})
        except ValidationError as exc:
            e = exc.errors(include_url=False)[0]
            raise LayoutError(f"layout={key}: {'.'.join(map(str, e['loc']))}: {e['msg']}") from None
        found = self.problems(layout)
        if found:
            more = f" (and {len(found) - 1} more)" if len(found) > 1 else ""
            raise LayoutError(f"layout={key}: {found[0]}{more}")
        return layout


def search(
    seed: int, attempt: Callable[[Draw, int], LayoutT | None], problems: Callable[[LayoutT], list[str]], what: str
) -> LayoutT:
    """The first of a seed's attempts that keeps every rule (`attempt` gives None when it gets stuck)."""
    draw = Draw(seed)
    for _ in range(1000):
        layout = attempt(draw, seed)
        if layout is not None and not problems(layout):
            return layout
    raise RuntimeError(f"no {what} layout found for seed {seed}")  # never seen: a bug of the rules


class Draw:
    """Choices from a seed, built on `Random.random()` only: Python guarantees that sequence for an
    integer seed on every version and machine (its other methods may change between versions)."""

    def __init__(self, seed: int):
        self._rng = Random(seed)

    def int(self, lo: int, hi: int) -> int:
        """An integer in lo..hi (both included)."""
        return lo + min(hi - lo, int(self._rng.random() * (hi - lo + 1)))

    def choice(self, options):
        options = list(options)
        return options[self.int(0, len(options) - 1)]

    def shuffled(self, items: Iterable) -> list:
        out = list(items)
        for i in range(len(out) - 1, 0, -1):
            j = self.int(0, i)
            out[i], out[j] = out[j], out[i]
        return out


Cell = tuple[int, int]  # x, z


def walkable_from(starts: Iterable[Cell], blocked: set[Cell], bounds: tuple[Cell, Cell]) -> set[Cell]:
    """Every cell a player can walk to from `starts` (steps to the four neighbours, inside bounds)."""
    (x0, z0), (x1, z1) = bounds
    seen = {s for s in starts if s not in blocked}
    queue = deque(seen)
    while queue:
        x, z = queue.popleft()
        for nxt in ((x + 1, z), (x - 1, z), (x, z + 1), (x, z - 1)):
            if nxt not in seen and nxt not in blocked and x0 <= nxt[0] <= x1 and z0 <= nxt[1] <= z1:
                seen.add(nxt)
                queue.append(nxt)
    return seen


def within_reach(target: Cell, reached: set[Cell], reach: int = 2) -> bool:
    """A block at `target` can be worked from a reached cell at most `reach` cells away (each axis)."""
    tx, tz = target
    return any((tx + dx, tz + dz) in reached for dx in range(-reach, reach + 1) for dz in range(-reach, reach + 1))


def unreachable(
    spawns: dict[str, Cell], targets: dict[str, list[Cell]], blocked: set[Cell], bounds: tuple[Cell, Cell]
) -> list[str]:
    """One line per (spawn, target) pair where the target cannot be reached on foot."""
    out = []
    for who, spawn in spawns.items():
        reached = walkable_from([spawn], blocked, bounds)
        for what, cells in targets.items():
            if not all(within_reach(c, reached) for c in cells):
                out.append(f"{what} cannot be reached on foot from {who}'s spawn {spawn}")
    return out


def apart(cells: Iterable[Cell], others: set[Cell], gap: int) -> bool:
    """No cell of `cells` within `gap` cells (each axis) of a cell of `others`."""
    return all(
        (x + dx, z + dz) not in others for x, z in cells for dx in range(-gap, gap + 1) for dz in range(-gap, gap + 1)
    )
