"""The two sides of every game, named once: red and blue (a side's team is `red=`/`blue=` in the
configuration, a side's directory in a run, a side's columns in a table)."""

from __future__ import annotations

from typing import Final

SIDES: Final = ("red", "blue")


def other_side(side: str) -> str:
    """The opposing side."""
    return SIDES[1 - SIDES.index(side)]
