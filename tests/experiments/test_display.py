"""A plain run's display keeps only what its live panel shows: a day of play (hundreds of episodes in
one series) holds no line per episode (benchmarks/day_of_play.py)."""

from __future__ import annotations

from types import SimpleNamespace

from pillagerbench.experiments.display import SHOWN, MatchDisplay


def record(episode: int) -> SimpleNamespace:
    return SimpleNamespace(
        episode=episode, status="ok", red="aggressive", blue="slimy", red_score=float(episode), blue_score=1.0,
        winner="red", error=None, duration_s=1.0, problems={},
    )  # fmt: skip


def test_the_panel_shows_the_last_episodes_and_the_display_keeps_no_more(capsys):
    display = MatchDisplay("a day of play", mode="plain")
    for episode in range(SHOWN + 40):
        display.episode_done(record(episode))
    shown = list(display._table({}).columns[0].cells)
    assert shown == [str(e) for e in range(40, SHOWN + 40)]
    assert len(display.finished) == SHOWN
    assert "episode 44: red aggressive 44.0 - blue slimy 1.0 (red)" in capsys.readouterr().out
