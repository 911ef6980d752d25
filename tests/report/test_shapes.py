"""The report at any shape: a calibration run (one red team: do_nothing) and a 12-team league give
legible heatmaps (no thin strip: cells of a fixed size), a per-team view that shows the opponents'
points whichever side they played, and a one-line caption under every figure with its number of
episodes. Replays: every episode is listed; one without a recording says so; the pages go under the
report's directory."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

from PIL import Image

from pillagerbench.report.build import build_report
from pillagerbench.report.plots import heatmap_size
from tests.metrics.fake_runs import write_run

FIXTURE = Path(__file__).resolve().parents[1] / "replay" / "fixtures" / "episode_000"
OPPONENTS = ["aggressive", "balanced", "passive", "slimy"]


def captions(page: str) -> list[str]:
    return re.findall(r"<figcaption>(.*?)</figcaption>", page)


def test_a_calibration_run_shows_the_opponents_and_captions_every_figure(tmp_path):
    runs = [
        write_run(tmp_path / f"cal_{o}", "mushroom_war", "do_nothing", o, [(0, 3 + i), (0, 4 + i)])
        for i, o in enumerate(OPPONENTS)
    ]
    result = build_report(runs, tmp_path / "report")
    out = tmp_path / "report"
    # heatmaps: one row, yet each panel at least as tall as a cell grid needs
    w, h = Image.open(out / "heatmaps_mushroom_war.png").size
    assert h >= 0.35 * w, (w, h)
    # per team: every opponent with its own points (not do_nothing's zeros), as blue
    per_team = (out / "per_team.csv").read_text()
    for i, o in enumerate(OPPONENTS):
        row = next(line for line in per_team.splitlines() if line.startswith(f"mushroom_war,{o},"))
        fields = row.split(",")
        assert fields[2:5] == ["2", "0", "2"], row  # episodes, as red, as blue
        assert float(fields[5]) == 3.5 + i  # P: own points
    assert (out / "teams_mushroom_war.png").stat().st_size > 0
    page = (out / "report.html").read_text()
    caps = captions(page)
    # the four figures with episodes behind them; groups and self-play have none: off the page, files kept
    assert len(caps) == page.count("data:image/png;base64,") == 4
    assert ">Groups</h2>" not in page and ">Self-play series</h2>" not in page
    assert (out / "groups.png").exists() and (out / "series_scores.png").exists()
    assert all(re.search(r"\b\d+ (team-group )?episode\(s\)", c) for c in caps), caps
    assert "8 episode(s)" in caps[0]
    # replays: listed for every episode; these hand-written runs have no recording
    assert "replays: 0 of 8 episode(s)" in " ".join(result["notes"])
    assert page.count("played before replays were recorded") == 8


def test_twelve_teams_keep_the_heatmap_cells_legible(tmp_path):
    teams = [f"team_{i:02d}" for i in range(12)]
    runs = [
        write_run(tmp_path / f"{red}_{blue}", "mushroom_war", red, blue, [(i, j)])
        for i, red in enumerate(teams)
        for j, blue in enumerate(OPPONENTS)
    ]
    build_report(runs, tmp_path / "report", with_replays=False)
    w, h = Image.open(tmp_path / "report" / "heatmaps_mushroom_war.png").size
    panel_w, panel_h = heatmap_size(12, len(OPPONENTS) + 1)
    assert h >= 110 * 2 * panel_h * 0.95  # the figure grows with the rows instead of squeezing them
    assert (panel_h - 1.9) / 12 >= 0.45  # at least 0.45 in per row
    page = (tmp_path / "report" / "report.html").read_text()
    assert "Replays" not in page
    caption = captions(page)[0]
    assert "48 episode(s) in 48 pairing(s)" in caption, caption


def test_the_report_links_a_recorded_episode_replay(tmp_path):
    run = write_run(tmp_path / "run", "mushroom_war", "passive", "balanced", [(4, 4), (1, 2)])
    shutil.copy(FIXTURE / "replay.jsonl.gz", run / "episode_000")
    result = build_report([run], tmp_path / "report")
    page = (tmp_path / "report" / "report.html").read_text()
    assert "href='replays/run/episode_000.html'" in page
    assert (tmp_path / "report" / "replays" / "run" / "episode_000.html").exists()
    assert not (tmp_path / "report" / "replays" / "run" / "episode_001.html").exists()
    assert not list(run.rglob("replay.html"))  # nothing written into the run directory
    assert "replays: 1 of 2 episode(s)" in " ".join(result["notes"])
