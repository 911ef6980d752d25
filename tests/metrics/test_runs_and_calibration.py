"""Loading run directories: scaling, skipped episodes with reasons, refusing mixed scenario
versions; σ_blue from do_nothing-red episodes and from calibration files."""

from __future__ import annotations

import json

import pytest

from pillagerbench.metrics import calibration as calib
from pillagerbench.metrics.runs import ReportError
from pillagerbench.metrics.verified import load_runs
from tests.metrics.fake_runs import write_run


def test_dash_and_dine_scores_are_scaled(tmp_path):
    write_run(tmp_path / "a", "dash_and_dine", "berries", "do_nothing", [(40, 0), (60, 10)])
    df = load_runs([tmp_path / "a"]).episodes
    assert list(df["red_score"]) == pytest.approx([4.0, 6.0])
    assert list(df["blue_raw"]) == [0.0, 10.0]
    assert df["red_t"].iloc[1][-1] == pytest.approx(6.0)


def test_skipped_episodes_are_listed_with_the_reason(tmp_path):
    run = write_run(tmp_path / "a", "mushroom_war", "passive", "balanced", [(3, 1), (4, 2), (5, 0)])
    (run / "episode_001" / "timeline.json").unlink()
    timeline = json.loads((run / "episode_002" / "timeline.json").read_text())
    (run / "episode_002" / "timeline.json").write_text(json.dumps(timeline[:2]))
    (run / "episode_003").mkdir()  # killed mid-episode: no line
    with open(run / "episodes.jsonl", "a") as f:
        f.write('{"episode": 4, "status": "failed", "error": "ArenaServerError: died"}\n{"episode": 5, "sta')
    runs = load_runs([run])
    assert list(runs.episodes["episode"]) == [0]
    why = {w.split("/")[-1]: y for w, y in runs.skipped}
    assert "no timeline.json" in why["episode_001"]
    assert "timeline ends at t=1" in why["episode_002"]
    assert "no line in episodes.jsonl" in why["episode_003"]
    assert "failed: ArenaServerError: died" in why["episode_004"]
    assert any("cut short" in y for _, y in runs.skipped)


def test_mixing_scenario_versions_is_refused(tmp_path):
    write_run(tmp_path / "v1", "mushroom_war", "passive", "do_nothing", [(3, 0)], version="1")
    write_run(tmp_path / "v2", "mushroom_war", "slimy", "do_nothing", [(3, 0)], version="2")
    with pytest.raises(ReportError, match="versions of mushroom_war"):
        load_runs([tmp_path / "v1", tmp_path / "v2"])
    # other scenarios may have other versions
    write_run(tmp_path / "d", "dash_and_dine", "berries", "do_nothing", [(3, 0)], version="7")
    assert len(load_runs([tmp_path / "v1", tmp_path / "d"]).episodes) == 2


def test_calibration_from_do_nothing_red_episodes_and_files(tmp_path):
    write_run(tmp_path / "cal", "mushroom_war", "do_nothing", "slimy", [(0, 4), (0, 6)])
    write_run(tmp_path / "dd", "dash_and_dine", "do_nothing", "berries", [(0, 100), (0, 140)])
    runs = load_runs([tmp_path / "cal", tmp_path / "dd"])
    cal = calib.calibration_from_runs(runs)
    assert cal["scenarios"]["mushroom_war"]["opponents"]["slimy"]["sigma_blue"] == 5.0
    assert cal["scenarios"]["dash_and_dine"]["opponents"]["berries"]["sigma_blue"] == 120.0  # stored unscaled
    (tmp_path / "calibration.json").write_text(json.dumps(cal))

    write_run(tmp_path / "main", "dash_and_dine", "berries", "berries", [(50, 100)])
    main = load_runs([tmp_path / "main"])
    sigma, notes = calib.resolve(main, tmp_path / "calibration.json")
    assert sigma[("dash_and_dine", "berries")].mean == pytest.approx(12.0)  # scaled ×0.1
    assert any("from" in n for n in notes)

    cal["scenarios"]["dash_and_dine"]["version"] = "9"
    (tmp_path / "calibration.json").write_text(json.dumps(cal))
    with pytest.raises(ReportError, match="version 9"):
        calib.resolve(main, tmp_path / "calibration.json")
