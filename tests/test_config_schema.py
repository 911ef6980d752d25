"""The configuration is typed once, at the edge (config_schema.RunConfig), and travels inward as that
model: each default is the schema's (conf/config.yaml, which Hydra composes and the suite hash reads,
holds the same values), a run directory's stored config from before a key still reads, the records
write the config as composed, and no module below the edge reads a config node by string key."""

from __future__ import annotations

import ast
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml  # type: ignore[import-untyped]
from pydantic import BaseModel

from pillagerbench.config.compose import ConfigError, config_options, load_config, to_dict
from pillagerbench.config.schema import RETRIES, ExperimentConfig, RunConfig, default
from pillagerbench.config.validate import check_run_config

SRC = Path(__file__).resolve().parents[1] / "src" / "pillagerbench"
FIXTURE = Path(__file__).parent / "experiments" / "fixtures" / "run_6198d49"
# the edge: where the command line and conf/ are composed, checked and typed (and help reads conf/)
EDGE = {"config/compose.py", "config/schema.py", "config/validate.py", "cli/help.py"}
GROUPS = {
    "scenario",
    "red",
    "blue",
    "llm",
    "experiment",
    "clock",
}  # config groups: their defaults are their YAML files'


def _defaults(model: type[BaseModel], prefix: str = "") -> dict[str, object]:
    """Every default the schema writes, by dotted key (sub-models' too)."""
    out: dict[str, object] = {}
    for name, field in model.model_fields.items():
        if not prefix and name in GROUPS:
            continue
        annotation = field.annotation
        if isinstance(annotation, type) and issubclass(annotation, BaseModel):
            out |= _defaults(annotation, f"{prefix}{name}.")
        elif not field.is_required():
            out[f"{prefix}{name}"] = field.get_default(call_default_factory=True)
    return out


def _select(tree: dict, key: str) -> object:
    for part in key.split("."):
        tree = tree[part]
    return tree


def test_each_default_of_conf_config_yaml_is_the_schemas():
    conf = yaml.safe_load((SRC / "conf" / "config.yaml").read_text())
    found = _defaults(RunConfig)
    assert {"scoring", "protocol", "retries", "episode_length", "launcher", "llm_ledger.content"} <= set(found)
    differ = {key: (value, _select(conf, key)) for key, value in found.items() if value != _select(conf, key)}
    assert not differ, f"schema default vs conf/config.yaml: {differ}"
    assert default("scoring") == "clean" and default("retries") == RETRIES


def test_the_default_clock_is_the_schemas():
    from pillagerbench.config.schema import ClockConfig

    conf = yaml.safe_load((SRC / "conf" / "clock" / "real.yaml").read_text())
    assert ClockConfig(**conf) == ClockConfig() == RunConfig.model_fields["clock"].default


def test_the_schema_writes_no_default_of_its_own():
    """Every default of the top-level keys, llm_cache and llm_ledger is conf/config.yaml's (`written`)."""
    tree = ast.parse((SRC / "config" / "schema.py").read_text(encoding="utf-8"))
    models = {"RunnerConfig", "RunConfig", "LLMCacheConfig", "LLMLedgerConfig"}
    own = []
    for cls in (n for n in tree.body if isinstance(n, ast.ClassDef) and n.name in models):
        for field in (n for n in cls.body if isinstance(n, ast.AnnAssign) and n.value is not None):
            value = field.value
            if isinstance(value, ast.Call) and getattr(value.func, "id", "") == "Field":
                value = next(
                    (k.value for k in value.keywords if k.arg == "default"), value.args[0] if value.args else None
                )
            if isinstance(value, ast.Constant) and ast.unparse(field.target) not in GROUPS:  # a group's: its YAML's
                own.append(f"{cls.name}.{ast.unparse(field.target)} = {value.value!r}")
    assert not own, "take these defaults from conf/config.yaml (written(KEY)): " + ", ".join(own)


def test_every_top_level_key_of_the_configuration_is_typed():
    composed = to_dict(load_config(["experiment=calibration"]))
    assert set(composed) <= set(RunConfig.model_fields)


def test_the_command_lines_configuration_arrives_typed():
    cfg = check_run_config(load_config(["red=cot", "red.llm.model=big", "blue=passive", "episode_length=30"]))
    assert isinstance(cfg, RunConfig)
    assert (cfg.red.name, cfg.blue.name, cfg.scenario.name, cfg.episode_length) == (
        "cot",
        "passive",
        "mushroom_war",
        30,
    )
    assert cfg.llm_of("red").model == "big" and cfg.llm_of("blue").model == "local"
    assert cfg.llm_of("red").price == cfg.llm.price  # merged key by key, not replaced
    assert cfg.red.options["attempts"] and not {"name", "llm"} & set(cfg.red.options)
    assert cfg.llm.model == "local"


def test_the_records_keep_the_config_as_composed():
    composed = to_dict(load_config(["episode_length=30", "layout=7"]))
    cfg = RunConfig.of(composed)
    assert cfg.stored() == composed and json.dumps(cfg.stored()) == json.dumps(composed)
    assert cfg.select("episode_length") == 30 and isinstance(cfg.select("episode_length"), int)
    assert cfg.select("scenario.name") == "mushroom_war" and cfg.select("no.such") is None
    cfg.stored()["seed"] = 99  # a copy: the model's own stays as it was
    assert cfg.stored()["seed"] == 0


def _stored_configs() -> list[tuple[str, dict]]:
    out = [(str(p.relative_to(FIXTURE)), json.loads(p.read_text())["config"]) for p in FIXTURE.rglob("manifest.json")]
    experiment = json.loads((FIXTURE / "experiment.json").read_text())
    out += [(f"experiment.json {s['id']}", s["config"]) for s in experiment["series"]]
    return out


@pytest.mark.parametrize(("where", "config"), _stored_configs())
def test_a_config_stored_before_todays_keys_reads_with_the_schemas_defaults(where, config):
    cfg = RunConfig.of(config)
    missing = {k for k in ("retries", "layout", "split", "paper", "plan") if k not in config}
    assert missing, f"{where}: the fixture is meant to predate these keys"
    for key in missing:
        assert getattr(cfg, key) == default(key), (where, key)
    assert cfg.stored() == config
    assert (cfg.scoring, cfg.protocol, cfg.retries) == ("clean", "pillagerbench", RETRIES)


def _below_the_edge() -> list[Path]:
    return [p for p in sorted(SRC.rglob("*.py")) if str(p.relative_to(SRC)) not in EDGE]


def test_no_module_below_the_edge_imports_omegaconf():
    found = []
    for path in _below_the_edge():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = (
                [a.name for a in node.names]
                if isinstance(node, ast.Import)
                else [node.module or ""]
                if isinstance(node, ast.ImportFrom)
                else []
            )
            found += [f"{path.relative_to(SRC)}:{node.lineno}" for n in names if n.split(".")[0] == "omegaconf"]
    assert not found, "take config_schema.RunConfig (or its part) instead of a DictConfig:\n" + "\n".join(found)


def test_no_module_below_the_edge_reads_a_config_by_string_key():
    pattern = re.compile(r"\b\w*cfg\.get\(|\bcfg\[\"")
    found = [
        f"{path.relative_to(SRC)}:{i}: {line.strip()}"
        for path in _below_the_edge()
        for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
        if pattern.search(line)
    ]
    assert not found, "read the typed configuration's fields instead:\n" + "\n".join(found)


def test_the_llm_settings_defaults_are_the_base_presets():
    """LLMSettings reads an `llm` node from before a key with its own defaults: conf/llm/base.yaml's."""
    from dataclasses import fields

    from pillagerbench.llm.settings import LLMSettings

    base = yaml.safe_load((SRC / "conf" / "llm" / "base.yaml").read_text())
    base |= {f"price_{k}": v for k, v in base.pop("price").items()}
    base.pop("budget")  # {} and a table of nulls both mean no limit
    ours = {f.name: getattr(LLMSettings(), f.name) for f in fields(LLMSettings) if f.name != "budget"}
    assert ours == base


def test_calibrate_hands_the_experiment_a_checked_typed_config_with_its_run_directory(monkeypatch, tmp_path):
    import pillagerbench.experiments.runner as runner
    from pillagerbench.metrics.calibration import main as calibrate

    given = []
    monkeypatch.setattr(runner, "main_experiment", lambda cfg, argv: given.append((cfg, argv)) or 1)
    assert calibrate([f"run_dir={tmp_path / 'cal'}", "episode_length=30"]) == 1
    [(cfg, argv)] = given
    assert isinstance(cfg, RunConfig) and cfg.experiment and cfg.experiment.name == "calibration"
    assert (cfg.run_dir, cfg.episode_length, argv[0]) == (str(tmp_path / "cal"), 30, "experiment=calibration")
    given.clear()
    monkeypatch.chdir(tmp_path)
    calibrate([])
    [(cfg, argv)] = given
    assert cfg.run_dir and argv[-1] == f"run_dir={cfg.run_dir}" and cfg.stored()["run_dir"] == cfg.run_dir


def test_a_stored_config_that_does_not_read_is_one_line_per_problem():
    stored = to_dict(load_config([]))
    stored["server"] = {**stored["server"], "tps": "fast"}
    del stored["seed"]  # a default: not a problem
    with pytest.raises(ConfigError) as err:
        RunConfig.of(stored)
    assert str(err.value) == "server.tps='fast': input should be a valid number, unable to parse string as a number"


@pytest.mark.parametrize("name", config_options("experiment"))
def test_every_experiment_reads_typed(name):
    from pillagerbench.experiments.spec import DESIGNS

    exp = RunConfig.of(load_config([f"experiment={name}"])).experiment
    assert isinstance(exp, ExperimentConfig) and exp.name == name and exp.design in DESIGNS and exp.repetitions


def test_a_bad_value_of_an_experiment_is_one_line():
    from pillagerbench.experiments.spec import build_series

    argv = ["experiment=round_robin_mushroom_war", "experiment.repetitions=twice"]
    with pytest.raises(ConfigError) as err:
        build_series(RunConfig.of(load_config(argv)), argv)
    assert str(err.value) == (
        "experiment.repetitions='twice': input should be a valid integer, unable to parse string as an integer"
    )


def test_a_team_or_scenario_named_by_a_number_is_one_line_about_the_name():
    with pytest.raises(ConfigError) as err:
        check_run_config(load_config(["red=7"]))
    [line] = str(err.value).splitlines()
    assert line.startswith("red=7: unknown team '7'; known: ")


def test_the_runners_keys_are_declared_once_and_left_out_one_way():
    """config/schema.py RunnerConfig declares every key the runner reads, once; RUNNER_KEYS is derived from
    it (all but `display`, which a series keeps), each a key of RunConfig; RunConfig.for_series is the one
    way a series' config leaves them."""
    from pillagerbench.config.compose import load_config
    from pillagerbench.config.schema import RUNNER_KEYS, RunConfig, RunnerConfig

    assert set(RUNNER_KEYS) == set(RunnerConfig.model_fields) - {"display"}
    assert set(RunnerConfig.model_fields) <= set(RunConfig.model_fields)
    tree = ast.parse((SRC / "config" / "schema.py").read_text(encoding="utf-8"))
    listed = [
        n
        for n in ast.walk(tree)
        if isinstance(n, ast.Tuple) and any(isinstance(e, ast.Constant) and e.value == "ray_address" for e in n.elts)
    ]
    assert not listed, "the runner's keys are RunnerConfig's fields, not a list beside them"
    full = RunConfig.of(load_config(["parallel=2", "run_dir=x", "plan=true"]))
    series = full.for_series().stored()
    assert not set(RUNNER_KEYS) & set(series) and set(full.stored()) - set(series) <= set(RUNNER_KEYS)
    assert series["display"] == full.stored()["display"]


def test_the_groups_checks_need_nothing_imported_first():
    """A fresh process that imports only config/validate.py checks teams as a run does (the checks'
    module is loaded on the first check), whatever the caller imported before."""
    code = (
        "from pillagerbench.config.compose import ConfigError\n"
        "from pillagerbench.config.validate import load_run\n"
        "print(load_run(['red=balanced']).red.name)\n"
        "try:\n    load_run(['red=no_such_team'])\nexcept ConfigError as e:\n    print(str(e).splitlines()[0])\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr[-2000:]
    first, refused = proc.stdout.splitlines()
    assert first == "balanced" and refused.startswith("red=no_such_team"), proc.stdout
