"""The table of episodes is built from typed rows (metrics/rows.py): `read_runs` gives each episode an
`EpisodeRow`, whose fields are checked as it is made, and the table is `frame` of them."""

from __future__ import annotations

import math

import pandas as pd
import pytest
from pydantic import ValidationError

from pillagerbench.metrics.columns import EPISODE_COLUMNS, Col
from pillagerbench.metrics.rows import EpisodeRow, frame, named
from pillagerbench.metrics.verified import load_runs
from tests.metrics.fake_runs import write_run


def test_the_runs_hold_typed_rows_and_their_tables_are_built_from_them(tmp_path):
    run = write_run(tmp_path / "a", "mushroom_war", "a", "b", [(2, 1), (0, 3), (1, 1)], lagged={1: "slow"})
    runs = load_runs([run])
    assert all(isinstance(r, EpisodeRow) for r in runs.rows + runs.spoiled_rows)
    assert [r.episode for r in runs.rows] == [0, 2] and [r.episode for r in runs.spoiled_rows] == [1]
    pd.testing.assert_frame_equal(runs.episodes, frame(runs.rows))
    pd.testing.assert_frame_equal(runs.spoiled, frame(runs.spoiled_rows))


def _row(tmp_path) -> EpisodeRow:
    run = write_run(tmp_path / "a", "mushroom_war", "a", "b", [(2, 1)])
    return load_runs([run]).rows[0]


def test_a_field_of_the_wrong_type_is_refused(tmp_path):
    good = _row(tmp_path).model_dump()
    for field, wrong in (("red_score", "2"), ("episode", 1.5), ("lagged", "no"), ("t", [0.0, "1"])):
        with pytest.raises(ValidationError, match=field):
            EpisodeRow(**{**good, field: wrong})
    with pytest.raises(ValidationError):  # a row is made whole, never changed after
        _row(tmp_path / "b").red_score = 3.0  # type: ignore[misc]


def test_the_frame_lays_a_row_out_as_the_declared_columns(tmp_path):
    row = _row(tmp_path)
    (cells,) = frame([row]).to_dict("records")
    assert list(cells) == list(EPISODE_COLUMNS)
    assert cells[Col.by_scoring("red", "clean")] == row.by_scoring["clean"]["red"] == 2.0
    assert math.isnan(cells[Col.by_scoring("red", "upstream")])  # a scoring the episode did not record
    assert list(cells[Col.RED_T]) == list(row.red_t)


def test_entrants_reading_alike_are_named_apart(tmp_path):
    row = _row(tmp_path)
    twin = row.model_copy(update={"red_entrant_id": "f" * 12})  # another entrant with the same label
    names = {(r.red, r.blue) for r in named([row, twin])}
    assert names == {(f"a#{row.red_entrant_id[:6]}", "b"), ("a#ffffff", "b")}
    assert [(r.red, r.blue) for r in named([row])] == [("a", "b")]
