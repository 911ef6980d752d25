"""The conditions of play (pillagerbench/suite/conditions.py): every key of every configuration is declared as
moving a score or not; each rule, changed alone, moves the stamp of the run and, changed as a default in
conf/, the suite's hash; a real run records its conditions on every episode, and a reader refuses to put
it beside a run of the suite's defaults unless asked."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from pillagerbench.config.compose import load_config
from pillagerbench.config.schema import RunConfig
from pillagerbench.metrics.runs import ReportError
from pillagerbench.metrics.verified import load_runs
from pillagerbench.suite import conditions
from pillagerbench.suite import version as suite
from tests.metrics.fake_runs import write_run

CONF = suite.PACKAGE / "conf"
EXPERIMENTS = sorted(p.stem for p in (CONF / "experiment").glob("*.yaml"))
SCENARIOS = sorted(p.stem for p in (CONF / "scenario").glob("*.yaml"))
# a value other than the suite's default, for each rule
OTHER = {
    "server.tps": 10,
    "server.view_distance": 6,
    "scenario.crop_growth_chance": 0.5,
    "episode_length": 30,
    "scoring": "upstream",
    "protocol": "upstream",
    "clock.mode": "lockstep",
    "clock.ticks_per_1k_tokens": 5,
    "humans.client": "minecraft",
}


def leaves(tree, prefix: str = "") -> list[str]:
    if not isinstance(tree, dict) or not tree:
        return [prefix[:-1]]
    return [key for k, v in tree.items() for key in leaves(v, f"{prefix}{k}.")]


@pytest.mark.parametrize(
    "overrides", [[]] + [[f"scenario={s}"] for s in SCENARIOS] + [[f"experiment={e}"] for e in EXPERIMENTS]
)
def test_every_key_of_every_configuration_is_declared_as_moving_a_score_or_not(overrides):
    from omegaconf import OmegaConf

    cfg = OmegaConf.to_container(load_config(overrides), resolve=False)
    undeclared = [key for key in leaves(cfg) if conditions.setting_of(key) is None]
    assert not undeclared, f"declare in conditions.SETTINGS whether these move a score: {undeclared}"


def test_every_declared_rule_is_a_key_of_the_configuration_and_has_a_reason():
    from omegaconf import OmegaConf

    cfg = load_config([])
    for s in conditions.SETTINGS:
        assert s.why and s.kind in (conditions.RULE, conditions.ARENA, conditions.NOT)
        if not s.key.endswith(".*"):
            assert OmegaConf.select(cfg, s.key, default="missing") != "missing", s.key
    assert set(OTHER) == set(conditions.RULES)  # a new rule gets its row here


def conditions_for(overrides: list[str]) -> dict:
    cfg = RunConfig.of(load_config(overrides))
    return conditions.conditions_of(cfg.select, cfg.scenario.name)


@pytest.mark.parametrize("key", sorted(OTHER))
def test_each_rule_changed_alone_moves_the_stamp_and_nothing_else_does(key):
    assert conditions_for([]) == {} and conditions_for(["seed=5", "episodes=3", "display=plain"]) == {}
    assert conditions_for([f"{key}={OTHER[key]}"]) == {key: OTHER[key]}
    label = suite.current()["label"]
    assert conditions.stamp(label, {key: OTHER[key]}) == f"{label} [{key}={OTHER[key]}]"
    assert conditions_for(["paper=true"]) == {"scoring": "upstream", "protocol": "upstream"}


@pytest.fixture
def package(tmp_path: Path) -> Path:
    """The package's score files and its conf/ copied."""
    root = tmp_path / "pillagerbench"
    for path in suite.score_files():
        target = root / path.relative_to(suite.PACKAGE)
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(path, target)
    shutil.copytree(CONF, root / "conf")
    return root


@pytest.mark.parametrize("key", sorted(OTHER))
def test_each_rules_default_changed_in_conf_moves_the_suite_hash(package, key):
    before = suite.suite_hash(package)
    parent, _, leaf = key.rpartition(".")
    files = {
        "scenario": [package / "conf" / "scenario" / f"{s}.yaml" for s in SCENARIOS],
        "clock": [package / "conf" / "clock" / f"{conditions.DEFAULT_CLOCK}.yaml"],
    }.get(parent, [package / "conf" / "config.yaml"])
    for path in files:
        text = path.read_text()
        line = next(ln for ln in text.splitlines() if ln.strip().startswith(f"{leaf}:"))
        indent = line[: len(line) - len(line.lstrip())]
        path.write_text(text.replace(line, f"{indent}{leaf}: {OTHER[key]}  # changed", 1))
    assert suite.suite_hash(package) != before


def test_a_comment_in_conf_and_the_scale_of_a_score_are_told_apart(package):
    before = suite.suite_hash(package)
    config = package / "conf" / "config.yaml"
    config.write_text(config.read_text() + "\n# a comment moves no score\n")
    assert suite.suite_hash(package) == before
    formulas = package / "metrics" / "formulas.py"
    formulas.write_text(formulas.read_text().replace('"dash_and_dine": 0.1', '"dash_and_dine": 0.2'))
    assert suite.suite_hash(package) != before


def test_a_real_run_records_its_conditions_and_is_not_put_beside_the_suites_defaults(tmp_path):
    run = tmp_path / "run"
    cmd = [
        sys.executable,
        "-m",
        "pillagerbench.cli",
        "run",
        "scenario=mushroom_war",
        "red=do_nothing",
        "blue=do_nothing",
    ]
    cmd += ["episode_length=3", "server.view_distance=6", "display=plain", f"run_dir={run}", "retries=0"]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    (line,) = (run / "episodes.jsonl").read_text().splitlines()
    record = json.loads(line)
    if record.get("lagged"):  # a loaded machine: spoiled (in no score); the stamp is what this test reads
        record["lagged"] = False
        (run / "episodes.jsonl").write_text(json.dumps(record) + "\n")
    assert record["conditions"] == {"episode_length": 3, "server.view_distance": 6}
    assert json.loads((run / "manifest.json").read_text())["conditions"] == record["conditions"]
    label = suite.current()["label"]
    assert load_runs([run]).suites == [f"{label} [episode_length=3, server.view_distance=6]"]
    write_run(tmp_path / "default", "mushroom_war", "do_nothing", "do_nothing", [(0, 0)], length=3, suite=label)
    with pytest.raises(
        ReportError,
        match=r"refusing to mix suite versions or conditions: .*\[episode_length=3, server.view_distance=6\]",
    ):
        load_runs([run, tmp_path / "default"])
    mixed = load_runs([run, tmp_path / "default"], mix_suites=True)
    assert len(mixed.episodes) == 2 and len(mixed.suites) == 2
