"""The layouts a league rates on: league.yaml's `split` (docs/league.md, docs/layouts.md).

`paper` (the default): every match on the paper's layout. `test`: every episode on a fresh test layout
(a seed drawn for it, recorded in its episodes.jsonl line), so no entrant can have been tuned to the
arenas it is rated on; `dev`: on seeded dev layouts. The board and the scheduler rate only the
episodes of the league's split; episodes of another split (rounds played with another `split=`) are
left out and the board names them, so ratings from the paper's and from test layouts are never mixed.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

from pillagerbench.config.compose import ConfigError
from pillagerbench.metrics.runs import Runs
from pillagerbench.scenarios.layout import PAPER, SPLITS

ON = {"paper": "the paper's layout", "dev": "dev layouts (public seeds)", "test": "fresh test layouts"}


def check_split(value: Any, where: str) -> str:
    """A league's `split` (null: paper), or a ConfigError of one line."""
    if value is None:
        return PAPER
    if value not in SPLITS:
        raise ConfigError(f"{where}: {SPLITS.unknown(value)} (the layouts a league rates on)")
    return str(value)


def check_game(game: tuple[str, ...]) -> None:
    """A league chooses its matches' layouts (its `split`): a `layout=` override is refused."""
    for a in game:
        if a.partition("=")[0].lstrip("+~") == "layout":
            raise ConfigError(
                f"{a!r}: a league plays on the paper's layout or on fresh layouts of its split "
                f"(split={'|'.join(SPLITS)}), not on one layout"
            )


def match_split(split: str) -> str | None:
    """The `split` of a match's config: null (every episode on layout=paper) or a split drawing each episode's."""
    return None if split == PAPER else split


def title(split: str) -> str:
    """What every table of the board says about its ratings."""
    return f" (ratings on {ON[split]}: split {split})"


def on_split(runs: Runs, split: str) -> tuple[Runs, list[str]]:
    """The runs with only the episodes of `split`, and a note naming the episodes left out (if any)."""
    df = runs.episodes
    if not len(df):
        return runs, [f"ratings on {ON[split]} (split {split})"]
    mine = df["split"] == split
    notes = [f"ratings on {ON[split]} (split {split}): {int(mine.sum())} of {len(df)} episodes"]
    others = df.loc[~mine, "split"].value_counts()
    if len(others):
        left = ", ".join(f"{n} on split {s}" for s, n in others.items())
        notes.append(f"left out: {left} (`board split={others.index[0]}` rates those; splits are never mixed)")
    kept = set(zip(df.loc[mine, "run"], df.loc[mine, "series"]))  # their ledgers too
    series = [s for s in runs.series if (str(s.run), s.id) in kept]
    return replace(runs, rows=[r for r in runs.rows if r.split == split], series=series), notes
