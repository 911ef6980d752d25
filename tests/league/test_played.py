"""`league play` reads each finished round once (league/results.py `Played`), not every round again
before each new one, and keeps only its outcomes; what it gives is what a read of every round gives: the
same outcomes of the league's split and budget, the same refusals across rounds (scenario versions,
episode lengths, suites: metrics/runs.py `check_comparable`, `suites`)."""

from __future__ import annotations

from pathlib import Path

import pytest

from pillagerbench.league import results
from pillagerbench.league.splits import on_split
from pillagerbench.metrics.runs import ReportError, read_runs
from pillagerbench.scenarios.layout import PAPER
from tests.metrics.fake_runs import write_run

A, B = "suite 1.0@aaaaaaaaaaaaaaaa", "suite 1.1@bbbbbbbbbbbbbbbb"


def _round(tmp_path: Path, i: int, **kw) -> Path:
    red, blue = ("do_nothing", "passive") if i % 2 else ("passive", "do_nothing")
    return write_run(tmp_path / f"round_{i:03d}", "mushroom_war", red, blue, [(i, 2), (1, i + 1)], suite=A, **kw)


@pytest.fixture
def league(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> tuple[list[Path], list[Path]]:
    """The league's rounds as plain runs (`shown`: the rounds written so far) and every read's inputs."""
    shown: list[Path] = []
    reads: list[Path] = []
    monkeypatch.setattr(results, "round_dirs", lambda _: list(shown))
    monkeypatch.setattr(results, "handed_over", lambda _: [])
    real = results.load_runs

    def counted(paths, *args):
        reads.extend(paths)
        return real(paths, *args)

    def spent_in(d: Path) -> results.Spent:  # a plain run has no series: the budget from its lines
        reads.append(d / "spent")
        return results.Spent(episodes=len((d / "episodes.jsonl").read_text().splitlines()), hours=0.25)

    monkeypatch.setattr(results, "load_runs", counted)
    monkeypatch.setattr(results, "_spent_in", spent_in)
    return shown, reads


def test_each_finished_round_is_read_once_and_gives_what_reading_them_all_gives(tmp_path, league):
    shown, reads = league
    played = results.Played(tmp_path)
    for i in range(3):
        shown.append(_round(tmp_path, i))
        got = played.outcomes(PAPER)
        assert got == results.outcomes(on_split(read_runs(shown), PAPER)[0])
        assert played.spent() == results.Spent(episodes=2 * (i + 1), hours=0.25 * (i + 1))
    assert reads == [p for d in shown for p in (d, d / "spent")]  # each round once, in order
    assert len(got) == 6 and played.outcomes("test") == []  # episodes of another split are not rated


def test_a_later_round_of_another_scenario_version_or_suite_is_refused_as_a_read_of_all_is(tmp_path, league):
    shown, _ = league
    played = results.Played(tmp_path)
    shown.append(_round(tmp_path, 0))
    played.outcomes(PAPER)
    for i, kw in ((1, {"version": "2"}), (2, {"length": 5})):
        shown[1:] = [_round(tmp_path, i, **kw)]
        with pytest.raises(ReportError) as whole:
            read_runs(shown)
        with pytest.raises(ReportError) as apart:
            results.Played(tmp_path).outcomes(PAPER)
        assert str(apart.value) == str(whole.value)
    shown[1:] = [write_run(tmp_path / "other", "mushroom_war", "passive", "do_nothing", [(1, 2)], suite=B)]
    with pytest.raises(ReportError, match="refusing to mix suite versions"):
        results.Played(tmp_path).outcomes(PAPER)
    assert len(results.Played(tmp_path, mix_suites=True).outcomes(PAPER)) == 3
