"""The inspect extra stays optional: nothing of the default install imports Inspect, and the bad inputs
are one line each, nothing started: llm=inspect without the extra, an unknown task argument, a model
role for a side whose team is not an LLM team."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from pillagerbench.inspect_tasks.args import TaskArgumentError
from tests.inspect_tasks.conftest import ROOT, mock_model

EVERY_MODULE_BUT_INSPECTS = """
import importlib, pkgutil, sys
import pillagerbench
OWN = ("pillagerbench.inspect_tasks", "pillagerbench.llm.inspect_model")
for m in pkgutil.walk_packages(pillagerbench.__path__, "pillagerbench."):
    if not m.name.startswith(OWN) and not m.name.endswith("__main__"):
        importlib.import_module(m.name)
from pillagerbench.cli import main
main(["run", "--help"])
print("inspect_ai imported" if "inspect_ai" in sys.modules else "inspect_ai not imported")
"""


def test_the_default_install_never_imports_inspect() -> None:
    out = subprocess.run([sys.executable, "-c", EVERY_MODULE_BUT_INSPECTS], capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.strip().splitlines()[-1] == "inspect_ai not imported"


def test_llm_inspect_without_the_extra_is_one_line(tmp_path: Path) -> None:
    # the extra "not installed": its import blocked
    script = (
        "import sys; sys.modules['inspect_ai'] = None\n"
        "from pillagerbench.cli import main\n"
        f"sys.exit(main(['run', 'red=cot', 'blue=passive', 'llm=inspect', 'run_dir={tmp_path / 'run'}']))\n"
    )
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, cwd=tmp_path)
    assert out.returncode == 2
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and "pip install 'pillagerbench[inspect]'" in lines[0], out.stderr
    assert "Traceback" not in out.stderr and not (tmp_path / "run").exists()


@pytest.mark.parametrize(
    ("task_args", "roles", "says"),
    [
        ({"bogus": 1}, {}, "unknown task argument 'bogus'; accepted: team, opponents"),
        ({"sides": "green"}, {}, "sides='green' is not one; accepted: red, blue"),
        ({"episodes": "two"}, {}, "episodes='two': a whole number ≥ 1"),
        ({"seed": -1}, {}, "seed=-1: a whole number ≥ 0"),
        ({"paper": "yes"}, {}, "paper='yes': true or false"),
        ({"team": "cott"}, {}, "unknown team 'cott'"),
        (
            {"opponents": "passive"},
            {"blue": True},
            "model role 'blue' given, but blue plays passive, which is not an LLM team",
        ),
        ({"team": "balanced"}, {"red": True}, "red plays balanced, which is not an LLM team"),
        ({"team": "agent", "opponents": "agent"}, {}, "opponents=agent: only the task's team is played by the"),
        ({"team": "agent"}, {"red": True, "blue": True}, "team=agent with model roles for both sides: the Inspect"),
    ],
)
def test_bad_task_arguments_are_one_line_and_start_nothing(tmp_path: Path, task_args, roles, says) -> None:
    from inspect_ai import eval as inspect_eval

    roles = {side: mock_model() for side in roles}
    with pytest.raises(TaskArgumentError) as info:
        inspect_eval(
            "pillagerbench/mushroom_war",
            task_args={"run_dir": str(tmp_path / "runs"), **task_args},
            model=mock_model(),
            model_roles=roles or None,
            log_dir=str(tmp_path / "logs"),
            display="none",
        )
    message = str(info.value.message)
    assert says in message and "\n" not in message
    assert not (tmp_path / "runs").exists()
