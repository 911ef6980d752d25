"""Episodes played under lag are reported wherever a reader looks: the report's table and
lagged.csv, its console lines, the experiment's closing list (hand-made runs), and the summary of a
real run whose server is held below the lag threshold (server.tps=10)."""

from __future__ import annotations

import csv
import html
import json

from pillagerbench.experiments.runner import lag_lines
from pillagerbench.experiments.spec import SeriesSpec
from pillagerbench.report.build import main as report_main
from tests.metrics.fake_runs import write_run
from tests.support.cli import run_cli
from tests.support.configs import run_config

WHY = "server at 12.5 TPS (< 19)"


def test_the_report_lists_the_lagged_episode_in_its_table_csv_and_console(tmp_path, capsys):
    run = write_run(
        tmp_path / "run", "mushroom_war", "passive", "do_nothing", [(3, 1), (2, 1), (4, 0)], lagged={1: WHY}
    )
    assert report_main([str(run), "--out", str(tmp_path / "report"), "--no-replays"]) == 0
    out = capsys.readouterr().out.splitlines()

    rows = list(csv.DictReader((tmp_path / "report" / "lagged.csv").open()))
    assert [(r["episode"], r["server_tps"], r["lag_reason"]) for r in rows] == [("1", "12.5", WHY)]
    series = rows[0]["series"]
    assert f"lagged {series} episode 1: {WHY}" in out
    assert any(line.startswith("1 episode(s) played under lag") and WHY in line for line in out)
    assert sum("played under lag" in line for line in out) == 1  # one note, nothing for the calm episodes
    page = (tmp_path / "report" / "report.html").read_text()
    table = page[page.rindex("Played under lag") :]  # the heading (the contents name it first)
    assert html.escape(WHY) in table[: table.index("</table>")]


def test_a_calm_run_reports_no_lag(tmp_path, capsys):
    run = write_run(tmp_path / "run", "mushroom_war", "passive", "do_nothing", [(3, 1), (2, 1)])
    assert report_main([str(run), "--out", str(tmp_path / "report"), "--no-replays"]) == 0
    assert "under lag" not in capsys.readouterr().out
    assert list(csv.DictReader((tmp_path / "report" / "lagged.csv").open())) == []


def spec(sid: str, episodes: int) -> SeriesSpec:
    return SeriesSpec(
        sid,
        0,
        "round_robin",
        "mushroom_war",
        "passive",
        "do_nothing",
        "passive",
        "do_nothing",
        episodes,
        0,
        run_config(),
    )


def test_the_experiments_closing_list_counts_every_lagged_episode_and_shows_ten(tmp_path):
    scores = [(1, 0)] * 12
    a = write_run(
        tmp_path / "a", "mushroom_war", "passive", "do_nothing", scores, lagged={i: f"why {i}" for i in range(12)}
    )
    b = write_run(tmp_path / "b", "mushroom_war", "passive", "do_nothing", scores[:3], lagged={2: WHY})
    calm = write_run(tmp_path / "c", "mushroom_war", "passive", "do_nothing", scores[:2])
    lines = lag_lines([spec("b", 3), spec("c", 2)], {"b": b, "c": calm})
    assert lines[0].startswith("1 episode(s) played under lag") and lines[1:] == [f"  b episode 2: {WHY}"]
    lines = lag_lines([spec("a", 12), spec("b", 3)], {"a": a, "b": b})
    assert lines[0].startswith("13 episode(s) played under lag")
    assert lines[1:11] == [f"  a episode {i}: why {i}" for i in range(10)]
    assert lines[11] == "  ... and 3 more (pillagerbench report lists all)"
    assert lag_lines([spec("c", 2)], {"c": calm}) == []


def test_a_run_with_its_server_held_at_10_tps_is_flagged_and_says_so(tmp_path):
    run_dir = tmp_path / "run"
    res = run_cli(
        tmp_path,
        "run",
        "red=passive",
        "blue=do_nothing",
        "episode_length=6",
        "server.tps=10",
        "retries=0",  # every episode lags here: not played again
        f"run_dir={run_dir}",
        "display=plain",
        timeout=240,
    )
    assert res.returncode == 0, res.stdout + res.stderr
    (rec,) = [json.loads(line) for line in (run_dir / "episodes.jsonl").read_text().splitlines()]
    assert rec["lagged"] is True and 8 < rec["server_tps"] < 12
    assert rec["lag_reason"].startswith(f"server at {rec['server_tps']:g} TPS (< 19)")
    assert "1 of 1 episode(s) played under lag" in res.stdout
    assert f"  episode 0: {rec['lag_reason']}" in res.stdout
    assert "0 of 1 planned episode(s) used; 1 spoiled on our side" in res.stdout  # in no score
