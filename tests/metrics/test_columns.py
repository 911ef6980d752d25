"""The table of episodes metrics hands the report has the columns metrics/columns.py declares, in its
order, for used and spoiled episodes alike; the report reads no column of it by a string of its own."""

from __future__ import annotations

import ast
from pathlib import Path

from pillagerbench.metrics.columns import EPISODE_COLUMNS, Col
from pillagerbench.metrics.verified import load_runs
from tests.metrics.fake_runs import write_run

SRC = Path(__file__).resolve().parents[2] / "src" / "pillagerbench"
# the readers of the table of episodes and the names they give it (or a part of it)
READERS = {
    "metrics/estimates.py": {"df", "sd", "rd", "g", "gd", "sub", "frame"},
    "metrics/generalization.py": {"df", "paper", "unseen"},
    "report/build.py": {"df", "main", "same", "g"},
    "report/generalization.py": {"df"},
    "report/provenance.py": {"df"},
    "metrics/calibration.py": {"df", "ref", "g"},
    "metrics/symmetry.py": {"df", "one", "other", "team_red", "team_blue"},
}


def test_the_table_of_episodes_has_the_declared_columns_in_order(tmp_path):
    run = write_run(tmp_path / "run", "mushroom_war", "a", "b", [(2, 1), (0, 3), (1, 1)], lagged={1: "slow"})
    runs = load_runs([run])
    assert list(runs.episodes.columns) == list(EPISODE_COLUMNS)
    assert list(runs.spoiled.columns) == list(EPISODE_COLUMNS)
    assert list(runs.episodes[Col.RED_SCORE]) == [2.0, 1.0]  # the lagged one is spoiled: in no score


def by_string(path: str, frames: set[str]) -> list[str]:
    """Every `frame["column"]` of a reader whose column is one of the table of episodes."""
    tree = ast.parse((SRC / path).read_text(encoding="utf-8"))
    return [
        f"{path}:{n.lineno}: {n.value.id}[{n.slice.value!r}]"
        for n in ast.walk(tree)
        if isinstance(n, ast.Subscript)
        and isinstance(n.value, ast.Name)
        and n.value.id in frames
        and isinstance(n.slice, ast.Constant)
        and n.slice.value in EPISODE_COLUMNS
    ]


def test_the_report_and_its_metrics_read_the_episodes_by_the_declared_names():
    found = [line for path, frames in READERS.items() for line in by_string(path, frames)]
    assert not found, "read these columns as metrics.columns.Col:\n" + "\n".join(found)
