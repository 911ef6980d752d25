"""`pillagerbench compare A B` (issue 41, item 1): on the real server, passive against balanced, each
against do_nothing, decides within a small cap under wide bounds, shows its log-likelihood ratio after
each pair, and resumes; bad input is one line, exit 2, nothing played."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from pillagerbench.experiments.comparison import Comparison, pair_scores
from pillagerbench.stats.sprt import Bounds
from tests.metrics.fake_runs import write_run
from tests.support.cli import refused_in_process, run_cli

WIDE = ["sprt.p1=0.9", "sprt.alpha=0.3", "sprt.beta=0.3", "cap=3"]


@pytest.mark.parametrize(
    ("args", "said"),
    [
        (["passive", "passive"], "A and B are the same entrant (passive); compare two different ones"),
        (["passive", "balanced", "sprt.p0=0.7", "sprt.p1=0.6"], "p0=0.7, p1=0.6: the bounds are in order"),
        (["passive", "balanced", "sprt.alpha=0.6"], "alpha=0.6: an error rate is in (0, 0.5)"),
        (["passive", "balanced", "sprt.beta=0"], "beta=0.0: an error rate is in (0, 0.5)"),
        (["passive"], "two entrants to compare, A and B (team names), got 1: passive"),
        (["passive", "nonexistent"], "unknown team 'nonexistent'; known: "),
    ],
)
def test_bad_input_is_one_line_and_nothing_is_played(tmp_path, monkeypatch, capsys, args, said):
    # in-process (cli.main, as the command calls it): a subprocess per case paid seconds of imports; the
    # command's refusal end to end (exit 2, one line, no traceback) is tests/test_cli_errors.py's
    (line,) = refused_in_process(monkeypatch, capsys, tmp_path, "compare", *args, f"run_dir={tmp_path / 'run'}")
    assert line.startswith("pillagerbench compare: ") and said in line, line
    assert not (tmp_path / "run").exists() and not (tmp_path / "runs").exists()


def test_pairs_alternate_sides_against_an_opponent_and_score_by_points(tmp_path):
    c = Comparison("a", "b", "o", Bounds(), cap=3)
    series = tmp_path / "series"
    write_run(series / "a_red", "mushroom_war", "a", "o", [(20, 0), (5, 0)])
    write_run(series / "b_red", "mushroom_war", "b", "o", [(10, 0), (5, 0)])
    write_run(series / "a_blue", "mushroom_war", "o", "a", [(0, 3)])
    write_run(series / "b_blue", "mushroom_war", "o", "b", [(0, 9)])
    assert [c.pair(k) for k in range(3)] == [("a_red", "b_red", 0), ("a_blue", "b_blue", 0), ("a_red", "b_red", 1)]
    assert pair_scores(c, tmp_path) == [1.0, 0.0, 0.5]
    head = Comparison("a", "b", None, Bounds(), cap=5)
    assert pair_scores(head, tmp_path) == [(1.0 + 0.0) / 2, (1.0 + 0.0) / 2]  # a won as red, lost as blue twice


def test_head_to_head_pairs_score_a_by_its_own_side_in_each_game(tmp_path):
    """A against B directly: pair k is A as red (a_red) and A as blue (b_red, B red); won both, lost both,
    won as blue only, each read from A's own side (an inverted reading scores 0, 1, 0.5 here)."""
    series = tmp_path / "series"
    write_run(series / "a_red", "mushroom_war", "a", "b", [(20, 0), (0, 4), (3, 3)])  # A red: wins, loses, ties
    write_run(series / "b_red", "mushroom_war", "b", "a", [(0, 9), (6, 1), (0, 2)])  # A blue: wins, loses, wins
    head = Comparison("a", "b", None, Bounds(), cap=5)
    assert pair_scores(head, tmp_path) == [1.0, 0.0, 0.75]


@pytest.mark.timeout(600)
def test_passive_against_balanced_decides_on_the_real_server_and_resumes(tmp_path):
    # On the game clock: 15 s of game do not shrink when the machine is loaded (a real-clock CI run tied
    # a pair and ended undecided), and the four episodes take seconds, not minutes.
    run = tmp_path / "cmp"
    args = [
        "passive",
        "balanced",
        "opponent=do_nothing",
        "episode_length=15",
        "clock=lockstep",
        *WIDE,
        f"run_dir={run}",
    ]
    res = run_cli(tmp_path, "compare", *args, timeout=540)
    assert res.returncode == 0, res.stdout + res.stderr
    lines = res.stdout.splitlines()
    pairs = [x for x in lines if x.startswith("pair ")]
    assert pairs and all("LLR" in x and "in [-0.85, +0.85]" in x for x in pairs), res.stdout
    last = lines[-1]
    # in 15 s balanced is still clearing its area's slime (0 points) while passive harvests at once (3): passive
    # wins every pair on either side, on the game clock every time, and the verdict must say so (read from the
    # wrong side it says "not better")
    assert last.startswith("compare: passive is better than balanced (SPRT "), last
    assert "undecided" not in last and f"{len(pairs)} pairs, {2 * len(pairs)} episodes, $0.0000)" in last, last
    played = [json.loads(x) for x in (run / "series" / "a_red" / "episodes.jsonl").read_text().splitlines()]
    assert all(e["conditions"]["clock.mode"] == "lockstep" for e in played), played
    saved = json.loads((run / "compare.json").read_text())
    assert saved["opponent"] == "do_nothing" and saved["cap"] == 3 and saved["bounds"]["p1"] == 0.9

    again = run_cli(tmp_path, "compare", f"resume={run}", timeout=120)  # decided: nothing more to play
    assert again.returncode == 0 and again.stdout.splitlines()[-1] == last, again.stdout + again.stderr
    report = run_cli(tmp_path, "report", str(run), "--no-replays", "--out", str(tmp_path / "report"), timeout=180)
    assert report.returncode == 0, report.stderr
    assert Path(tmp_path / "report" / "summary.md").exists()
    # decided is finished: the report opens with the answer and reads no series as unfinished
    assert report.stdout.splitlines()[0] == last and "unfinished" not in report.stdout, report.stdout
    # its bundle, on the game clock end to end: exported, verified, every episode used
    bundle = tmp_path / "cmp.tar.gz"
    exported = run_cli(tmp_path, "export", str(run), "--out", str(bundle), timeout=120)
    assert exported.returncode == 0 and f"{2 * len(pairs)} episode(s) used" in exported.stdout, exported.stdout
    verified = run_cli(tmp_path, "verify", str(bundle), timeout=120)
    assert verified.returncode == 0, verified.stdout + verified.stderr
