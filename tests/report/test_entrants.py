"""The report groups by entrant (issue 37, item 1): cot on two models is two rows in every table, never
one "cot" row; σ_blue, side symmetry and "Unseen arenas" too. Hand-made runs whose records are from before entrants (no red_entrant/blue_entrant):
their entrants come from the manifests' configs, so old run directories still report (no server)."""

from __future__ import annotations

import csv
import json
from pathlib import Path

from pillagerbench.config.schema import RunConfig
from pillagerbench.metrics.calibration import calibration_from_runs
from pillagerbench.metrics.generalization import unseen_arenas
from pillagerbench.metrics.symmetry import side_symmetry
from pillagerbench.metrics.verified import load_runs
from pillagerbench.report.build import build_report
from pillagerbench.teams.entrant import entrant_of
from tests.metrics.fake_runs import write_run
from tests.report.test_says_what_it_is import with_manifest
from tests.report.test_unseen_arenas import TEST_SEEDS


def cot_run(path: Path, model: str, scores: list[tuple[float, float]]) -> Path:
    run = write_run(path, "mushroom_war", "cot", "balanced", scores, length=6)
    return with_manifest(run, llm={"provider": "openai", "model": model}, red={"name": "cot", "llm": {}})


def rows(path: Path) -> list[dict[str, str]]:
    return list(csv.DictReader(path.open()))


def test_one_team_on_two_models_is_two_rows_in_every_table(tmp_path):
    four = cot_run(tmp_path / "four", "gpt-4o", [(6, 1), (5, 2)])
    mini = cot_run(tmp_path / "mini", "gpt-4o-mini", [(1, 4), (0, 3)])
    build_report([four, mini], tmp_path / "report", with_replays=False)
    out = tmp_path / "report"
    summary = {r["red"]: r for r in rows(out / "summary.csv")}
    assert set(summary) == {"cot@gpt-4o", "cot@gpt-4o-mini"}
    assert summary["cot@gpt-4o"]["episodes"] == "2" and float(summary["cot@gpt-4o"]["P"]) == 5.5
    assert float(summary["cot@gpt-4o-mini"]["P"]) == 0.5
    pairs = {(r["red"], r["blue"]) for r in rows(out / "pairings.csv")}
    assert {("cot@gpt-4o", "balanced"), ("cot@gpt-4o-mini", "balanced")} <= pairs
    teams = {r["team"] for r in rows(out / "per_team.csv")}
    assert teams == {"cot@gpt-4o", "cot@gpt-4o-mini", "balanced"}


def test_an_old_record_gets_the_entrant_its_config_gives(tmp_path):
    run = cot_run(tmp_path / "old", "gpt-4o", [(3, 3)])
    config = json.loads((run / "manifest.json").read_text())["config"]
    df = load_runs([run]).episodes
    assert list(df["red_entrant_id"]) == [entrant_of(RunConfig.of(config), "red").id]
    assert list(df["red_entrant"]) == ["cot@gpt-4o"] and list(df["blue_entrant"]) == ["balanced"]
    assert list(df["red_name"]) == ["cot"]  # the name the series gave the side


def test_entrants_that_read_alike_get_their_ids(tmp_path):
    """Two entrants whose labels are the same text (a string option "2" and a number 2) are told
    apart by their ids: they never share a row."""
    runs = []
    for name, value in (("text", "2"), ("number", 2)):
        run = write_run(tmp_path / name, "mushroom_war", "random", "balanced", [(1, 1)], length=6)
        runs.append(with_manifest(run, red={"name": "random", "pause_every": value}))
    df = load_runs(runs).episodes
    assert df["red"].nunique() == 2 and all(r.startswith("random(pause_every=2)#") for r in df["red"])


def llm_run(path: Path, red: tuple[str, str], blue: tuple[str, str], scores, **kw) -> Path:
    """A run of (team, model) against (team, model); a model of None: a team without an LLM."""
    run = write_run(path, "mushroom_war", red[0], blue[0], scores, length=6, **kw)
    nodes = {
        side: {"name": t, "llm": {"model": m}} if m else {"name": t}
        for side, (t, m) in zip(("red", "blue"), (red, blue))
    }
    return with_manifest(run, llm={"provider": "openai", "model": "gpt-4o"}, **nodes)


def test_calibration_symmetry_and_unseen_arenas_keep_entrants_apart(tmp_path):
    four, mini, nothing = ("cot", "gpt-4o"), ("cot", "gpt-4o-mini"), ("do_nothing", None)
    runs = [
        llm_run(tmp_path / "a", nothing, four, [(0, 6), (0, 4)]),
        llm_run(tmp_path / "b", nothing, mini, [(0, 1), (0, 1)]),
        llm_run(tmp_path / "c", four, mini, [(5, 1), (6, 2)]),
        llm_run(tmp_path / "d", mini, four, [(1, 5), (2, 6)]),
    ]
    loaded = load_runs(runs)
    sigma = calibration_from_runs(loaded)["scenarios"]["mushroom_war"]["opponents"]
    assert {k: v["sigma_blue"] for k, v in sigma.items()} == {"cot@gpt-4o": 5.0, "cot@gpt-4o-mini": 1.0}
    table, _ = side_symmetry(loaded.episodes[loaded.episodes["red_team"] == "cot"])
    assert sorted(table["team"]) == ["cot@gpt-4o", "cot@gpt-4o-mini"]  # not a mirror match of "cot"
    assert set(table.loc[table["team"] == "cot@gpt-4o", "as_red"]) == {5.5}

    arenas = [
        llm_run(tmp_path / f"{split}_{m}", (("cot", m)), nothing, [(3, 0)] * 3, layouts=layouts)
        for m in ("gpt-4o", "gpt-4o-mini")
        for split, layouts in (("paper", ["paper"] * 3), ("test", TEST_SEEDS))
    ]
    unseen = unseen_arenas(load_runs(arenas).episodes, {})
    assert set(unseen["team"]) == {"cot@gpt-4o", "cot@gpt-4o-mini", "do_nothing"}
