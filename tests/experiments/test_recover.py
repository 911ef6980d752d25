"""Crash recovery of a series directory, without a server: what is kept, what is moved aside."""

from __future__ import annotations

import json

from pillagerbench.rundir import RunDir
from tests.support.configs import run_config


def test_recover_keeps_finished_and_discards_the_rest(tmp_path):
    s = tmp_path / "series"
    for i in range(3):
        (s / f"episode_{i:03d}").mkdir(parents=True)
        (s / f"episode_{i:03d}" / "episode.json").write_text("{}")
    lines = [json.dumps({"episode": 0, "status": "ok"}), json.dumps({"episode": 1, "status": "ok"})]
    (s / "episodes.jsonl").write_text(lines[0] + "\n" + lines[1] + "\n" + '{"episode": 2, "st')
    ledger = b'{"team": "red", "call": 1}\n{"team": "red", "call": 2}\n'
    (s / "llm_calls.jsonl").write_bytes(ledger + b'{"team": "red", "call": 3}\n')
    for i in (1, 2):
        RunDir(s).state(i).mkdir(parents=True)
    (RunDir(s).state(1) / "ledger_offset").write_text(str(len(ledger)))
    (s / "live.json").write_text("{}")

    finished, note = RunDir(s).recover()

    assert sorted(finished) == [0, 1]
    assert (s / "episodes.jsonl").read_text() == lines[0] + "\n" + lines[1] + "\n"
    assert (s / "episode_001").exists() and not (s / "episode_002").exists()
    assert [p.name.split(".")[0] for p in (s / "discarded").iterdir() if p.is_dir()] == ["episode_002"]
    assert (s / "llm_calls.jsonl").read_bytes() == ledger
    assert RunDir(s).state(1).exists() and not RunDir(s).state(2).exists()
    assert not (s / "live.json").exists()
    assert len(note) == 3  # torn line, episode_002, one ledger call
    assert RunDir(s).recover() == (finished, [])  # idempotent


def test_a_plain_run_directory_resumes_as_one_series(tmp_path):
    from pillagerbench.experiments.runner import load_experiment

    config = {
        **run_config().stored(),  # a real run's manifest holds every key
        "scenario": {"name": "mushroom_war", "crop_growth_chance": 0.0},
        "red": {"name": "passive"},
        "blue": {"name": "balanced"},
        "episodes": 3,
        "episode_length": 10,
        "seed": 4,
        "display": "auto",
        "experiment": None,
        "parallel": None,
        "resume": None,
    }
    (tmp_path / "manifest.json").write_text(json.dumps({"config": config}))
    title, specs, dirs = load_experiment(tmp_path)
    assert title == "run" and len(specs) == 1
    spec = specs[0]
    assert (spec.red, spec.blue, spec.episodes, spec.seed) == ("passive", "balanced", 3, 4)
    assert dirs[spec.id] == tmp_path and "resume" not in spec.config.stored()
