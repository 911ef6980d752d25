"""The table of episodes, typed: `EpisodeRow` is one episode's row as metrics/runs.py reads it from the
episode's record, its series and its timeline, each field checked as it is made (a field of the wrong
type is refused, not carried into a table); `frame` is the one place the table the report reads
(`Runs.episodes`, `Runs.spoiled`) is built from the rows, with metrics/columns.py's columns in their
order. A field is named as its column (`Col`), but for the points by every scoring (`by_scoring`,
one column per scoring and side in the table, NaN where the episode did not record it)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import pandas as pd
from pydantic import BaseModel, ConfigDict

from pillagerbench.match import SCORINGS
from pillagerbench.metrics.columns import EPISODE_COLUMNS, SIDES, Col


class EpisodeRow(BaseModel):
    """One episode's row of the table (metrics/columns.py says what each column holds)."""

    model_config = ConfigDict(frozen=True, strict=True)

    run: str
    dir: str
    series: str
    scenario: str
    version: str
    episode_length: float
    red: str  # the series' name for the side until every row is read, then the entrant's (`named`)
    blue: str
    red_entrant: str
    red_entrant_id: str
    red_name: str
    blue_entrant: str
    blue_entrant_id: str
    blue_name: str
    red_team: str
    blue_team: str
    design: str
    variant: str | None
    repetition: int
    group: str | None
    group_x: int | float | None
    episode: int
    index: int
    red_raw: float
    blue_raw: float
    scale: float
    red_score: float
    blue_score: float
    scoring: str
    suite: str
    stamp: str
    rules: str
    conditions: dict[str, Any]
    layout: str | int
    seed: int
    split: str
    by_scoring: dict[str, dict[str, float]]  # scoring -> side -> final points, scaled (the scorings recorded)
    team_protocol: str
    iterations: float
    problems: dict[str, list[str]]
    server_tps: float | None
    lagged: bool
    lag_reason: str | None
    t: tuple[float, ...]
    red_t: tuple[float, ...]
    blue_t: tuple[float, ...]


def named(rows: Sequence[EpisodeRow]) -> list[EpisodeRow]:
    """The rows with `red` and `blue` their entrants' names, which every table groups by: an entrant's
    label, or `label#id6` (its id's first 6 hex digits) when another entrant's label reads alike."""
    labels: dict[str, str] = {}
    for r in rows:
        labels |= {r.red_entrant_id: r.red_entrant, r.blue_entrant_id: r.blue_entrant}
    shared = {label for label in labels.values() if list(labels.values()).count(label) > 1}
    names = {i: f"{label}#{i[:6]}" if label in shared else label for i, label in labels.items()}
    return [r.model_copy(update={"red": names[r.red_entrant_id], "blue": names[r.blue_entrant_id]}) for r in rows]


def frame(rows: Sequence[EpisodeRow]) -> pd.DataFrame:
    """The table of episodes of these rows: EPISODE_COLUMNS in order, a timeline as an array of floats."""
    return pd.DataFrame([_cells(r) for r in rows])


def _cells(row: EpisodeRow) -> dict[str, Any]:
    by_scoring = {
        Col.by_scoring(side, mode): row.by_scoring[mode][side] if mode in row.by_scoring else np.nan
        for mode in SCORINGS
        for side in SIDES
    }
    timelines = {Col.T: row.t, Col.RED_T: row.red_t, Col.BLUE_T: row.blue_t}
    return {
        c: by_scoring[c]
        if c in by_scoring
        else np.array(timelines[c], dtype=float)
        if c in timelines
        else getattr(row, c)
        for c in EPISODE_COLUMNS
    }
