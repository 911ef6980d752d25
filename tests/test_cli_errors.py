"""Every mistake at the command line: one line per problem, exit code 2, no run directory; a team
whose model never answered is stopped by the preflight, or recorded when the preflight is off.

The refusals are checked in-process (`cli.main`, as `python -m pillagerbench.cli` calls it): a
subprocess per case paid 1-3 s of imports for the same answer. Two refusals still go through the real
command, end to end (`test_the_command_refuses_in_one_line_with_exit_2`, `test_a_port_in_use_is_one_line`)."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from pillagerbench.llm.fake_server import FakeLLMServer, Rule
from tests.support.cli import refused_in_process, run_cli


def pb(tmp_path, *args, env=None, timeout=120):
    return run_cli(tmp_path, *args, env=env, timeout=timeout)


def one_line_refusal(tmp_path, *args, lines=1):
    """The real command, in a subprocess: exit 2, `lines` lines on stderr, no traceback, no run directory."""
    proc = pb(tmp_path, *args)
    assert proc.returncode == 2, proc.stderr
    err = proc.stderr.strip().splitlines()
    assert len(err) == lines, proc.stderr
    assert "Traceback" not in proc.stderr and proc.stdout == ""
    assert not (tmp_path / "runs").exists(), "a refused run must not leave a run directory"
    return err


@pytest.fixture
def refuse(tmp_path, monkeypatch, capsys):
    """refuse(*argv, lines=1): the command refuses in-process in tmp_path (tests/support/cli.py's
    `refused_in_process`); those lines."""
    return lambda *argv, lines=1: refused_in_process(monkeypatch, capsys, tmp_path, *argv, lines=lines)


def test_the_command_refuses_in_one_line_with_exit_2(tmp_path):
    """End to end, through `python -m pillagerbench.cli`: what the in-process checks below take for given."""
    (line,) = one_line_refusal(tmp_path, "run", "episode_length=abc")
    assert line.startswith("pillagerbench run: episode_length='abc': input should be a valid number"), line


@pytest.mark.parametrize(
    "args, expected",
    [
        (["episode_length=abc"], "pillagerbench run: episode_length='abc': input should be a valid number"),
        (["episodes=-1"], "pillagerbench run: episodes=-1: input should be greater than or equal to 1"),
        (["parallel=0"], "pillagerbench run: parallel=0: input should be greater than or equal to 1"),
        (["retries=-1"], "pillagerbench run: retries=-1: input should be greater than or equal to 0"),
        (
            ["experiment=round_robin_mushroom_war", "retries=-1"],
            "pillagerbench run: retries=-1: input should be greater than or equal to 0",
        ),
        (["display=fancy"], "pillagerbench run: display='fancy': input should be 'auto', 'live' or 'plain'"),
        (["scoring=paper"], "pillagerbench run: scoring='paper': input should be 'clean' or 'upstream'"),
        (["protocol=paper"], "pillagerbench run: protocol='paper': input should be 'pillagerbench' or 'upstream'"),
        (["server.port=70000"], "pillagerbench run: server.port=70000: input should be less than or equal to 65535"),
        (["llm_cache.mode=sometimes"], "pillagerbench run: llm_cache.mode='sometimes': input should be 'off', 'read'"),
        (["red=cot", "red.attempts=x"], "pillagerbench run: red.attempts='x': input should be a valid integer"),
        (["red=cot", "red.atempts=3"], "pillagerbench run: red.atempts: no such option (team cot has options attempts"),
        (["blue=passive", "blue.llm.model=x"], "pillagerbench run: blue.llm.model: team passive uses no LLM"),
        (
            ["red=nonexistent"],
            "pillagerbench run: red=nonexistent: unknown team 'nonexistent'; known: agent, aggressive",
        ),
        (["scenario=foo"], "pillagerbench run: unknown scenario 'foo'; known: dash_and_dine, mushroom_war"),
        (["experiment=nope"], "pillagerbench run: unknown experiment 'nope'; known: ablation_models"),
        (["llm=nope"], "pillagerbench run: unknown llm preset 'nope'; known: fake"),
        (["epsiodes=3"], "pillagerbench run: epsiodes: no such key"),
        (["clock=fast"], "pillagerbench run: unknown clock 'fast'; known: lockstep, real"),
        (["clock=lockstep", "clock.speed=0"], "pillagerbench run: clock.speed=0: a multiple of real time above 0"),
        (["clock=lockstep", "clock.speed=fast"], "pillagerbench run: clock.speed='fast': a multiple of real time"),
        (["clock=lockstep", "paper=true"], "pillagerbench run: paper=true plays on the real clock"),
        (["clock=lockstep", "server.tps=40"], "pillagerbench run: server.tps=40: clock=lockstep plays 20 ticks"),
    ],
)
def test_a_bad_value_is_one_line_naming_key_value_and_choices(refuse, args, expected):
    (line,) = refuse("run", *args)
    assert line.startswith(expected), line


def test_a_team_that_cannot_play_the_scenario_leaves_no_run_directory(refuse):
    err = refuse("run", "scenario=dash_and_dine", "red=passive", "blue=berries")
    assert err[0].startswith(
        "pillagerbench run: red=passive: plays only mushroom_war, not dash_and_dine; "
        "teams for dash_and_dine: do_nothing, berries"
    )


def test_every_problem_is_reported_at_once(refuse):
    err = refuse("run", "episodes=0", "episode_length=-5", "display=x", "red=cot", "llm.temperature=9", lines=4)
    keys = [line.split(": ")[1].split("=")[0] for line in err]
    assert sorted(keys) == ["display", "episode_length", "episodes", "llm.temperature"]


def test_a_missing_key_stops_the_run_before_anything_starts(refuse):
    (line,) = refuse("run", "red=cot", "llm=openai")
    assert "LLM preflight failed for openai model gpt-4o-mini at https://api.openai.com/v1" in line
    assert "OPENAI_API_KEY is not set" in line and "llm.preflight=false" in line


def test_an_unreachable_provider_stops_the_run_before_episode_0(refuse):
    (line,) = refuse("run", "red=cot", "llm=fake", "llm.base_url=http://127.0.0.1:9/v1")
    assert "LLM preflight failed for fake model fake-model at http://127.0.0.1:9/v1" in line
    assert "nothing answers there" in line


def test_an_unknown_model_is_named_by_the_preflight(refuse):
    with FakeLLMServer() as fake:
        fake.add(Rule(status=404, message="model not found"))
        (line,) = refuse("run", "red=cot", "llm=fake", f"llm.base_url={fake.url}")
    assert "fake model fake-model" in line and "check llm.model and llm.base_url" in line


def test_a_reachable_provider_passes_the_preflight_with_one_request(tmp_path):
    from pillagerbench.config.compose import load_config
    from pillagerbench.config.schema import RunConfig
    from pillagerbench.match import preflight

    with FakeLLMServer() as fake:
        cfg = load_config(["red=cot", "blue=cot", "llm=fake", f"llm.base_url={fake.url}"])
        preflight.check(preflight.sides_of(RunConfig.of(cfg)))  # both sides share provider, model and URL: one request
        assert fake.count == 1 and fake.requests[0].role == "preflight"


def test_without_preflight_a_team_without_its_model_is_recorded_and_shown(tmp_path):
    proc = pb(
        tmp_path,
        "run",
        "red=cot",
        "blue=do_nothing",
        "llm=fake",
        "llm.base_url=http://127.0.0.1:9/v1",
        "llm.preflight=false",
        "llm.max_retries=0",
        "episode_length=4",
        "display=plain",
        "run_dir=out",
        "clock=lockstep",  # what a missing model does to the record, not to game time: faster than real time
        timeout=240,
    )
    assert proc.returncode == 1, proc.stdout + proc.stderr  # every episode of red went without its model
    assert "red cot: llm failed on all" in proc.stdout
    # ours, not the team's: the planned episode is played again twice (retries=2), then given up
    assert "red cot had problems in 3 of 3 episode(s), e.g.: llm failed on all" in proc.stdout
    assert "0 of 1 planned episode(s) used; 3 spoiled on our side" in proc.stdout and "; 1 given up" in proc.stdout
    for line in (tmp_path / "out" / "episodes.jsonl").read_text().splitlines():
        rec = json.loads(line)
        assert rec["status"] == "ok" and "LLMConnectionError" in rec["problems"]["red"][0]
        assert "blue" not in rec["problems"]


def test_an_internal_error_is_one_line_naming_the_traceback_file(tmp_path, monkeypatch, capsys):
    from pillagerbench.cli import commands as cli

    monkeypatch.setenv("PILLAGERBENCH_CACHE", str(tmp_path / "cache"))
    monkeypatch.setitem(cli.COMMANDS, "boom", ("json:loads", "test"))
    assert cli.main(["boom"]) == 1  # json.loads([]) raises TypeError: a bug, not a user error
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("pillagerbench boom: internal error: TypeError")
    path = err[0].split("full traceback: ")[1].split(";")[0]
    assert "Traceback" in open(path).read()


@pytest.mark.parametrize(
    "args, expected",
    [
        (["server", "server.port=abc"], "pillagerbench server: server.port='abc': input should be a valid integer"),
        (["llm-ping", "llm.timeout=abc"], "pillagerbench llm-ping: llm.timeout='abc': input should be a valid number"),
        (["llm-ping", "llm=nope"], "pillagerbench llm-ping: unknown llm preset 'nope'"),
        (["report", "nowhere"], "pillagerbench report: nowhere: not a run directory"),
        (["calibrate", "nowhere"], "pillagerbench calibrate: nowhere: not a run directory"),
        (["symmetry", "nowhere"], "pillagerbench symmetry: nowhere: not a run directory"),
        (["try", "scenario=mushroom_war", "player=Ryn", "code=none.js"], "pillagerbench try: [Errno 2] No such file"),
        (["try", "layout=abc", "code=none.js"], "pillagerbench try: layout='abc': valid: paper, a seed"),
        (
            ["try", "scenario=flat", "layout=3", "code=none.js"],
            "pillagerbench try: layout=3: scenario 'flat' has no layouts",
        ),
        (["nope"], "pillagerbench: unknown command 'nope'; valid commands: run, setup"),
    ],
)
def test_other_commands_refuse_bad_input_in_one_line(refuse, args, expected):
    (line,) = refuse(*args)
    assert line.startswith(expected), line


def test_a_port_in_use_is_one_line(tmp_path):
    import socket

    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        (line,) = one_line_refusal(tmp_path, "server", f"server.port={port}")
    assert line == (
        f"pillagerbench server: arena server failed to start: port 127.0.0.1:{port} is already in use "
        "(choose another with server.port=..., or 0 for a free port)"
    )


@pytest.mark.parametrize(
    "args, expected",
    [
        (["experiment=main_benchmark", "experiment.team=remote"], "red.url: the remote team needs the address"),
        (
            ["experiment=main_benchmark", "experiment.team=cot", "experiment.team_options.atempts=2"],
            "red.atempts: unknown key (options of cot: attempts",
        ),
        (
            ["experiment=main_benchmark", "experiment.team=cot", "llm=fake", "llm.base_url=http://127.0.0.1:9/v1"],
            "LLM preflight failed for fake model fake-model at http://127.0.0.1:9/v1",
        ),
    ],
)
def test_an_experiment_checks_its_teams_and_providers_before_anything_starts(refuse, args, expected):
    (line,) = refuse("run", *args)
    assert expected in line, line


# --- The small wrong things of issue 31, in-process (cli.main) --------------------------------------------

KEY = "sk-proj-Abcdefghijklmnop1234567890"


def refused(capsys, *argv):
    """cli.main(argv) refuses in one line (exit 2, nothing on stdout); that line."""
    from pillagerbench.cli import commands as cli

    assert cli.main(list(argv)) == 2
    out, err = capsys.readouterr()
    (line,) = err.strip().splitlines()
    assert out == "" and "Traceback" not in err
    return line


@pytest.mark.parametrize(
    "argv, where",
    [
        (["run", "red=cot", "llm=openai", f"llm.api_key_env={KEY}"], "pillagerbench run: llm.api_key_env: "),
        (["run", "red=cot", f"red.llm.api_key_env={KEY}"], "pillagerbench run: red.llm.api_key_env: "),
        (["llm-ping", "llm=openai", f"llm.api_key_env={KEY}"], "pillagerbench llm-ping: llm.api_key_env: "),
    ],
)
def test_a_key_given_as_api_key_env_is_never_echoed(capsys, monkeypatch, tmp_path, argv, where):
    monkeypatch.chdir(tmp_path)
    line = refused(capsys, *argv)
    assert KEY not in line and line.startswith(where)
    assert "looks like a key, not the name of an environment variable" in line and "export OPENAI_API_KEY=" in line
    assert not (tmp_path / "runs").exists()


def test_llm_ping_without_the_key_variable_is_a_user_error(capsys, monkeypatch):
    monkeypatch.delenv("OPENAI_API_KEY", raising=False)
    line = refused(capsys, "llm-ping", "llm=openai")
    assert line.startswith("pillagerbench llm-ping: openai: environment variable OPENAI_API_KEY is not set")


def test_report_with_a_missing_calibration_file_names_it_and_reference(capsys, tmp_path):
    from tests.metrics.fake_runs import write_run

    run = write_run(tmp_path / "run", "mushroom_war", "passive", "do_nothing", [(3, 1)])
    missing = tmp_path / "foo.json"
    line = refused(capsys, "report", str(run), "--calibration", str(missing), "--out", str(tmp_path / "out"))
    assert line.startswith(f"pillagerbench report: --calibration {missing}: no such file")
    assert "--calibration reference" in line and "Errno" not in line


def test_an_unknown_experiment_team_is_named_as_the_user_typed_it(capsys, monkeypatch, tmp_path):
    monkeypatch.chdir(tmp_path)
    line = refused(capsys, "run", "experiment=main_benchmark", "experiment.team=cott")
    assert line.startswith("pillagerbench run: experiment.team=cott: unknown team 'cott'; known: agent, aggressive")
    assert "red=" not in line and "cot," in line
    assert not (tmp_path / "runs").exists()


def test_an_environment_variable_given_as_an_override_gets_the_export_hint(capsys):
    line = refused(capsys, "run", f"OPENAI_API_KEY={KEY}")
    assert line.startswith("pillagerbench run: OPENAI_API_KEY: no such key; it looks like an environment variable")
    assert "export OPENAI_API_KEY=..." in line and KEY not in line


def test_an_experiment_key_without_an_experiment_gets_the_hint(capsys):
    line = refused(capsys, "run", "experiment.team=cot")
    assert line.startswith("pillagerbench run: experiment.team: no such key: no experiment is chosen; ")
    assert "choose one first with experiment=NAME" in line and "main_benchmark" in line
    line = refused(capsys, "run", "experiment=main_benchmark", "experiment.tem=cot")
    assert line.startswith("pillagerbench run: experiment.tem: no such key (experiment main_benchmark has keys ")
    assert "team, team_options" in line


@pytest.mark.parametrize(
    "argv", [["suite", "--hash"], ["--version"], ["layout", "show", "mushroom_war", "3", "--out", "OUT"]]
)
def test_a_light_command_starts_without_pandas_or_openai(tmp_path, argv):
    """The error types a command may raise are looked up after it ran (cli._refuse), so `suite`,
    `--version` and `layout` start in a fraction of a second instead of paying for pandas and openai."""
    argv = [str(tmp_path / "map.html") if a == "OUT" else a for a in argv]
    code = f"import sys\nfrom pillagerbench.cli.commands import main\nmain({argv!r})\nprint(sorted({{'pandas', 'openai'}} & set(sys.modules)))"
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60, cwd=tmp_path)
    assert proc.returncode == 0 and proc.stdout.splitlines()[-1] == "[]", (proc.stdout, proc.stderr)
