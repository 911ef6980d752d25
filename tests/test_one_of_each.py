"""One of each (issue 53, item 5): the sides, the tick's length and a game's result are each defined in one
place, and no module spells its own copy."""

from __future__ import annotations

import re
from pathlib import Path

import pillagerbench

SRC = Path(pillagerbench.__file__).parent
HOMES = {
    "the sides": ("config/sides.py", re.compile(r'\(\s*"red",\s*"blue"\s*\)|^SIDES\b.*=', re.M)),
    "the tick's length": ("config/game_tick.py", re.compile(r"^TICK_(S|MS)\s*=\s*[\d.]+", re.M)),
    "a game's result": ("stats/result.py", re.compile(r"1(\.0)? if .+ else 0\.5 if")),
}


def test_each_is_defined_once():
    copies = {
        what: sorted(
            str(p.relative_to(SRC))
            for p in SRC.rglob("*.py")
            if str(p.relative_to(SRC)) != home and pattern.search(p.read_text())
        )
        for what, (home, pattern) in HOMES.items()
    }
    assert copies == {what: [] for what in HOMES}, copies


def test_nothing_asks_a_clock_its_class():
    """The match (and everyone else) asks the clock (GameClock: begin, end, close, stalls), never its class."""
    asking = sorted(
        str(p.relative_to(SRC)) for p in SRC.rglob("*.py") if re.search(r"isinstance\([^)]*Clock\b", p.read_text())
    )
    assert asking == [], asking
