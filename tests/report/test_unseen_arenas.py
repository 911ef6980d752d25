"""The report's "Unseen arenas" section (issue 29): P, S, D, W on the paper's layout and on test
layouts with the gap and its interval, from hand-made runs (no server); none at all for runs played on
the paper's layout only."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from pillagerbench.report.build import build_report
from tests.metrics.fake_runs import write_run
from tests.report.test_says_what_it_is import headings, table_after

TEST_SEEDS = [1_000_001, 1_000_002, 1_000_003]  # three test layouts (seeds of the test split)
PAPER = [(10, 4), (12, 6), (8, 5)]  # mine (red) vs passive (blue), on the paper's layout
UNSEEN = [(6, 4), (5, 7), (7, 5)]  # the same pairing on the test layouts


def report(tmp_path: Path, *runs: Path) -> tuple[Path, list[str]]:
    """The report of `runs`, with σ_blue of passive = 20 ± 3 (n = 10)."""
    out, calibration = tmp_path / "out", tmp_path / "calibration.json"
    sigma = {"passive": {"sigma_blue": 20.0, "ci": 3.0, "std": 4.2, "n": 10}}
    calibration.write_text(
        json.dumps({"scenarios": {"mushroom_war": {"version": "1", "episode_length": 4, "opponents": sigma}}})
    )
    result = build_report(list(runs), out, calibration=calibration, with_replays=False)
    return out, result["notes"]


def welch(se_a: float, se_b: float) -> float:
    """The 95 % half-width of a difference of two means of 3 episodes each, by hand: Welch–Satterthwaite
    df (between 3 and 4 here), t interpolated in 1/df between t(3) = 3.182 and t(4) = 2.776."""
    var = se_a**2 + se_b**2
    df = var**2 / (se_a**4 / 2 + se_b**4 / 2)
    assert 3 < df < 4
    w = (1 / 3 - 1 / df) / (1 / 3 - 1 / 4)
    return (3.182 + w * (2.776 - 3.182)) * math.sqrt(var)


def test_the_section_puts_the_paper_beside_unseen_layouts_with_the_gap(tmp_path):
    paper = write_run(tmp_path / "paper", "mushroom_war", "mine", "passive", PAPER, layouts=["paper"] * 3)
    unseen = write_run(tmp_path / "test", "mushroom_war", "mine", "passive", UNSEEN, layouts=TEST_SEEDS)
    out, notes = report(tmp_path, paper, unseen)
    page = (out / "report.html").read_text()
    title = next(h for h in headings(page) if h.startswith("Unseen arenas"))
    rows = {(r["team"], r["metric"]): r for r in table_after(page, title)}
    assert {r["split"] for r in rows.values()} == {"test"}
    # D by hand: paper 6, 6, 3 (mean 5, s = √3, se 1); test 2, −2, 2 (mean 2/3, s = √(16/3), se 4/3):
    # gap 2/3 − 5 = −4.33, df 3.71, t 2.871, half-width 2.871 · √(1 + 16/9) = 4.79
    half = welch(1, 4 / 3)
    assert half == pytest.approx(4.79, abs=0.005)
    d = rows[("mine", "D")]
    assert (d["paper"], d["unseen"], d["gap"]) == ("5.00 ± 4.30", "0.67 ± 5.74", f"-4.33 ± {half:.2f}")
    assert rows[("mine", "P")]["gap"].startswith("-4.00 ± ")  # P: 10 on the paper's layout, 6 on test layouts
    # S = σ − passive's points: 20 − 5 = 15 on the paper's layout, 20 − 16/3 on test layouts. The same σ is
    # on both sides of the gap and cancels, so its ± 3 is not in the gap's interval: passive's points alone,
    # paper 4, 6, 5 (se 1/√3), test 4, 7, 5 (se √(7/9)): df 3.45, half-width 3.13
    s = rows[("mine", "S")]
    assert s["paper"].startswith("15.00 ± ") and s["gap"] == f"-0.33 ± {welch(1 / math.sqrt(3), math.sqrt(7 / 9)):.2f}"
    assert rows[("passive", "P")]["paper"].startswith("5.00") and rows[("passive", "W")]["gap"].startswith("0.33")
    md = (out / "unseen_arenas.md").read_text()
    assert md.startswith("## Unseen arenas") and f"-4.33 ± {half:.2f}" in md
    assert any(n.startswith("unseen arenas: 3 on 3 test layout(s), 3 on the paper's layout") for n in notes)


@pytest.mark.parametrize("layouts", [None, ["paper"] * 3], ids=["records before layouts", "paper only"])
def test_runs_on_the_papers_layout_only_have_no_section(tmp_path, layouts):
    run = write_run(tmp_path / "run", "mushroom_war", "mine", "passive", PAPER, layouts=layouts)
    out, notes = report(tmp_path, run)
    assert not (out / "unseen_arenas.md").exists() and not (out / "unseen_arenas.csv").exists()
    page = (out / "report.html").read_text()
    assert "Unseen arenas" not in page and not any("unseen" in n for n in notes)
