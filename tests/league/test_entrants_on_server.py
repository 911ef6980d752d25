"""Entrants on the real server (issue 37, item 1): a league of cot on two models (the fake LLM provider
under two model names) plays a match; every episode records each side's entrant, the board has one
row per entrant with its label and id, the report one row per entrant, and its LLM calls in its row, and the same round with its
records stripped of their entrants (a run from before them) reports the same entrants. The league plays on
the lockstep clock (issue 38, item 6: a league's thinking players hold the clock); a later `play` on the
other clock is refused, so the board never rates the two clocks together."""

from __future__ import annotations

import csv
import json
import shutil
from pathlib import Path

import pytest
import yaml  # type: ignore[import-untyped]

from pillagerbench.config.schema import RunConfig
from pillagerbench.llm.fake_server import FakeLLMServer
from pillagerbench.metrics.verified import load_runs
from pillagerbench.report.build import build_report
from pillagerbench.teams.entrant import entrant_of
from tests.support.cli import run_cli

MODELS = {"cot_4o": "gpt-4o", "cot_mini": "gpt-4o-mini"}
PLAY = ["play", "budget.episodes=2", "episodes_per_match=1", "episode_length=5", "parallel=1", "display=plain"]
CLOCK = "clock=lockstep"


@pytest.fixture(scope="module")
def league(tmp_path_factory):
    root = tmp_path_factory.mktemp("league") / "L"
    root.mkdir()
    with FakeLLMServer() as llm:
        entrants = [
            {"name": n, "team": "cot", "options": {}, "llm": "fake", "llm_options": {"base_url": llm.url, "model": m}}
            for n, m in MODELS.items()
        ]
        spec = {"scenarios": ["mushroom_war"], "matches_per_round": 1, "entrants": entrants}
        (root / "league.yaml").write_text(yaml.safe_dump(spec))
        played = run_cli(Path.cwd(), "league", str(root), *PLAY, CLOCK, timeout=300)
        assert played.returncode == 0, played.stdout + played.stderr
    board = run_cli(Path.cwd(), "league", str(root), "board")
    assert board.returncode == 0, board.stderr
    return root


def series_dirs(root: Path) -> list[Path]:
    return sorted((root / "matches").glob("round_*/series/*"))


def test_every_episode_records_the_entrant_its_config_gives(league):
    both = series_dirs(league)
    assert len(both) == 2  # the match and its side-swapped twin
    for series in both:
        config = json.loads((series / "manifest.json").read_text())["config"]
        (record,) = [json.loads(x) for x in (series / "episodes.jsonl").read_text().splitlines()]
        for side in ("red", "blue"):
            assert record[f"{side}_entrant"] == entrant_of(RunConfig.of(config), side).to_dict()
        labels = {record["red_entrant"]["label"], record["blue_entrant"]["label"]}
        assert labels == {"cot@gpt-4o", "cot@gpt-4o-mini"}
        assert record["red_entrant"]["id"] != record["blue_entrant"]["id"]
        assert config["clock"]["mode"] == "lockstep" and record["lagged"] is False


def test_a_play_on_the_other_clock_is_refused_and_plays_nothing(league):
    before = series_dirs(league)
    other = run_cli(Path.cwd(), "league", str(league), *PLAY, "budget.episodes=4", "clock=real")
    assert other.returncode == 2, other.stdout + other.stderr
    (line,) = other.stderr.strip().splitlines()
    assert "clock=lockstep" in line and "clock=real" in line
    assert series_dirs(league) == before


def test_the_board_has_a_row_per_entrant_with_its_label_and_id(league):
    rows = {r["entrant"]: r for r in csv.DictReader((league / "leaderboard.csv").open())}
    assert {n: rows[n]["label"] for n in MODELS} == {n: f"cot@{m}" for n, m in MODELS.items()}
    assert rows["cot_4o"]["id"] != rows["cot_mini"]["id"]
    assert all(rows[n]["episodes"] == "2" for n in MODELS)  # one on each side


def test_the_report_has_a_row_per_entrant_and_an_old_copy_reports_the_same(league, tmp_path):
    (round_dir,) = sorted((league / "matches").glob("round_*"))
    build_report([round_dir], tmp_path / "report", with_replays=False)
    per_team = list(csv.DictReader((tmp_path / "report" / "per_team.csv").open()))
    assert sorted(r["team"] for r in per_team) == ["cot@gpt-4o", "cot@gpt-4o-mini"]
    summary = list(csv.DictReader((tmp_path / "report" / "summary.csv").open()))  # a row per red entrant
    assert sorted(r["red"] for r in summary) == ["cot@gpt-4o", "cot@gpt-4o-mini"]
    assert all(int(r["llm_calls"]) >= 1 for r in summary)  # its own calls

    old = shutil.copytree(round_dir, tmp_path / "old")
    for path in old.glob("series/*/episodes.jsonl"):  # records from before entrants
        records = [json.loads(x) for x in path.read_text().splitlines()]
        for r in records:
            del r["red_entrant"], r["blue_entrant"]
        path.write_text("".join(json.dumps(r) + "\n" for r in records))
    columns = ["red", "blue", "red_entrant_id", "blue_entrant_id"]
    recorded, derived = load_runs([round_dir]).episodes, load_runs([old]).episodes
    assert derived[columns].to_dict("records") == recorded[columns].to_dict("records")
