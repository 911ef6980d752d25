"""A decided comparison is complete (issue 55, item 2): once its test decides, its series planned what
they played (report, verify and export read them as finished), compare.json records the answer, and the
report opens with the answer and the test's path before its tables. Run directories written by hand."""

from __future__ import annotations

import html
import json
import re

from pillagerbench.experiments.compare import start
from pillagerbench.experiments.comparison import Comparison, answer, settle
from pillagerbench.metrics.verified import load_runs
from pillagerbench.report.build import build_report
from pillagerbench.stats.sprt import BETTER, UNDECIDED, Bounds
from tests.metrics.fake_runs import write_run

WIDE = Bounds(p1=0.9, alpha=0.3, beta=0.3)  # two pairs won decide: LLR 2 x log(0.9 / 0.5) = 1.18 > 0.85


def compare_dir(tmp_path, pairs_won: int, cap: int = 9):
    """passive against balanced, each against do_nothing: passive ahead in each of `pairs_won` pairs."""
    c = Comparison("passive", "balanced", "do_nothing", WIDE, cap, ["episode_length=4"])
    run, _ = start(c, tmp_path / "cmp")
    series = run / "series"
    for sid, (red, blue) in c.series().items():
        n = len([k for k in range(pairs_won) if c.pair(k)[0] == sid or c.pair(k)[1] == sid])
        a_side = sid.startswith("a_")
        points = (3, 0) if red != "do_nothing" else (0, 3)
        if not a_side:
            points = (1, 0) if red != "do_nothing" else (0, 1)
        write_run(series / sid, "mushroom_war", red, blue, [points] * n)
    return c, run


def test_a_decided_comparison_is_finished_for_every_reader(tmp_path):
    c, run = compare_dir(tmp_path, pairs_won=2)
    found = answer(c, run)
    assert (found.verdict, found.scores, found.finished) == (BETTER, (1.0, 1.0), True)
    before = load_runs([run])
    assert any("1 of 9 episode(s) used so far (unfinished run?" in why for _, why in before.skipped), before.skipped

    settle(run, found)

    after = load_runs([run])
    assert not [why for _, why in after.skipped if "unfinished" in why], after.skipped
    planned = {s["id"]: s["episodes"] for s in json.loads((run / "experiment.json").read_text())["series"]}
    assert planned == {"a_red": 1, "b_red": 1, "a_blue": 1, "b_blue": 1}
    decided = json.loads((run / "compare.json").read_text())["decided"]
    assert decided == {"verdict": BETTER, "pairs": 2, "episodes": 4}
    assert found.line().startswith("compare: passive is better than balanced (SPRT α=0.3, β=0.3, p0=0.5, p1=0.9;")
    assert found.line().endswith("; 2 pairs, 4 episodes, $0.0000)")


def test_the_report_opens_with_the_answer_and_the_tests_path(tmp_path):
    c, run = compare_dir(tmp_path, pairs_won=2)
    settle(run, answer(c, run))
    out = tmp_path / "report"
    result = build_report([run], out, with_replays=False)
    assert result["notes"][0] == answer(c, run).line()
    page = (out / "report.html").read_text()
    headings = [html.unescape(h) for h in re.findall(r"<h2 id='section-\d+'>([^<]*)</h2>", page)]
    assert headings[:3] == [
        "Answer: passive (A) against balanced (B)",
        "The test's path: passive against balanced",
        "Provenance: what each run is, from its manifests",
    ], headings
    assert (out / "compare_0.png").stat().st_size > 1000
    summary = (out / "summary.csv").read_text().splitlines()
    head = summary[0].split(",")
    rows = {r.split(",")[0]: dict(zip(head, r.split(","), strict=False)) for r in summary[1:]}
    assert rows["passive"]["planned"] == rows["passive"]["episodes"], rows  # planned is what was played


def test_a_comparison_killed_before_its_answer_says_so(tmp_path):
    c, run = compare_dir(tmp_path, pairs_won=1)
    found = answer(c, run)
    assert (found.verdict, found.finished) == (UNDECIDED, False)
    assert "undecided against balanced so far (1 of up to 9 pairs; unfinished: compare resume=RUN_DIR)" in found.line()
