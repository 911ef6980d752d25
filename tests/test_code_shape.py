"""The code keeps its shape: lint, format, types, the import contracts and the JavaScript style.

Each check runs one tool with the command CONTRIBUTING.md gives (every command there is run here) and
shows the tool's findings when it fails.
The tools and their settings: pyproject.toml ([tool.ruff], [tool.mypy], [tool.importlinter]) and
src/pillagerbench/js/eslint.config.js; all pinned (the `test` extra, package.json's devDependencies).
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
import sysconfig
import textwrap
from pathlib import Path

import pytest

from pillagerbench.host.node import ensure_node_modules, modules_dir

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src"
SCRIPTS = Path(sysconfig.get_path("scripts"))


def tool(name: str) -> str:
    path = SCRIPTS / name
    return str(path) if path.exists() else (shutil.which(name) or name)


def run(cmd: list[str], cwd: Path = ROOT, env: dict | None = None, timeout: float = 300) -> subprocess.CompletedProcess:
    return subprocess.run(
        cmd, cwd=cwd, env={**os.environ, **(env or {})}, capture_output=True, text=True, timeout=timeout
    )


def shown(proc: subprocess.CompletedProcess) -> str:
    return f"$ {' '.join(proc.args)}\n{proc.stdout}\n{proc.stderr}"


# --- The checks, as CONTRIBUTING.md gives them: ruff, ruff format, import-linter, mypy, eslint -----------

CONTRIBUTING = ROOT / "CONTRIBUTING.md"


def commands(tag: str) -> list[str]:
    """The command lines of the ```sh block after `<!-- tag -->` in CONTRIBUTING.md."""
    text = CONTRIBUTING.read_text(encoding="utf-8")
    block = re.search(rf"<!-- {re.escape(tag)} -->\n```sh\n(.*?)\n```", text, re.S)
    assert block, f"CONTRIBUTING.md has no ```sh block after <!-- {tag} -->"
    return [line for line in block.group(1).splitlines() if line.strip()]


def as_run(command: str) -> list[str]:
    """A command line with `.venv/bin/` meaning the environment running the tests (CI's is .venv)."""
    words = shlex.split(command)
    if words[0] == ".venv/bin/python":
        return [sys.executable, *words[1:]]
    if words[0].startswith(".venv/bin/"):
        return [tool(words[0].removeprefix(".venv/bin/")), *words[1:]]
    return words


def test_contributing_has_only_commands_that_run():
    text = CONTRIBUTING.read_text(encoding="utf-8")
    assert len(re.findall(r"^```sh$", text, re.M)) == 4  # setup, checks, fixes, one-test: all run below
    checks = " | ".join(commands("checks"))
    for needed in ("ruff check", "ruff format --check", "lint-imports", "mypy", "scripts/eslint.py"):
        assert needed in checks, f"CONTRIBUTING.md's checks lost `{needed}`"


def test_setup_is_the_readme_test_command():
    (setup,) = commands("setup")
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert re.search(rf"<!-- test-command -->\n```\n{re.escape(setup)} && ", readme), (setup, readme)


@pytest.mark.parametrize("command", commands("checks"))
def test_check(command):
    proc = run(as_run(command))
    assert proc.returncode == 0, shown(proc)


@pytest.mark.parametrize("command", commands("one-test"))
def test_one_test_command(command):
    proc = run(as_run(command))
    assert proc.returncode == 0 and " passed" in proc.stdout, shown(proc)


def test_fix_commands(tmp_path):
    """They rewrite files, so they run on a copy of the tree."""
    for name in ("src", "tests", "benchmarks", "scripts", "examples"):
        shutil.copytree(ROOT / name, tmp_path / name, ignore=shutil.ignore_patterns("__pycache__", "node_modules"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path)
    for command in commands("fixes"):
        proc = run(as_run(command), cwd=tmp_path)
        assert proc.returncode == 0, shown(proc)


def test_bad_format_and_type_errors_are_caught(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text("def f( x:int )->str:\n    return x\n")
    fmt = run([tool("ruff"), "format", "--no-cache", "--check", "--config", str(ROOT / "pyproject.toml"), str(bad)])
    assert fmt.returncode == 1 and "1 file would be reformatted" in fmt.stdout, shown(fmt)
    types = run([tool("mypy"), "--config-file", str(ROOT / "pyproject.toml"), "--no-incremental", str(bad)])
    assert types.returncode == 1 and 'Incompatible return value type (got "int", expected "str")' in types.stdout, (
        shown(types)
    )


# --- The import contracts and cycles ---------------------------------------------------------------

CYCLES = textwrap.dedent("""
    import grimp, json
    graph = grimp.build_graph("pillagerbench", cache_dir=None)  # imports inside functions included
    index, low, stack, on_stack, cycles = {}, {}, [], set(), []

    def visit(start):  # Tarjan's strongly connected components, iterative
        work = [(start, iter(sorted(graph.find_modules_directly_imported_by(start))))]
        index[start] = low[start] = len(index)
        stack.append(start); on_stack.add(start)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is None:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    part = []
                    while True:
                        m = stack.pop(); on_stack.discard(m); part.append(m)
                        if m == node:
                            break
                    if len(part) > 1:
                        cycles.append(sorted(part))
            elif child not in index:
                index[child] = low[child] = len(index)
                stack.append(child); on_stack.add(child)
                work.append((child, iter(sorted(graph.find_modules_directly_imported_by(child)))))
            elif child in on_stack:
                low[node] = min(low[node], index[child])

    for module in sorted(graph.modules):
        if module not in index:
            visit(module)
    print(json.dumps(cycles))
""")


def import_cycles(src: Path) -> list[list[str]]:
    """Groups of modules that import each other in a circle (any import counts, even in a function)."""
    import json

    proc = run([sys.executable, "-c", CYCLES], env={"PYTHONPATH": str(src)})
    assert proc.returncode == 0, shown(proc)
    return json.loads(proc.stdout)


def lint_imports(src: Path) -> subprocess.CompletedProcess:
    return run(
        [tool("lint-imports"), "--no-cache", "--config", str(ROOT / "pyproject.toml")], env={"PYTHONPATH": str(src)}
    )


def test_no_import_cycles():
    assert import_cycles(SRC) == []


def test_forbidden_imports_are_caught(tmp_path):
    """On a copy of the tree: an upward import, one team importing another, and a cycle."""
    shutil.copytree(
        SRC / "pillagerbench",
        tmp_path / "pillagerbench",
        ignore=shutil.ignore_patterns("__pycache__", "node_modules", "js"),
    )
    pkg = tmp_path / "pillagerbench"

    def append(rel: str, code: str) -> None:
        path = pkg / rel
        path.write_text(path.read_text() + "\n\n" + textwrap.dedent(code))

    append(
        "scenarios/mushroom_war.py",
        """
        def _upward():
            from pillagerbench.teams import TEAMS  # a scenario reaching up to the teams
            return TEAMS
    """,
    )
    append(
        "teams/cot/team.py",
        """
        from pillagerbench.teams.tacticrafter import memory as _other_team  # noqa
    """,
    )
    append(
        "experiments/progress.py",
        """
        def _circle():
            from pillagerbench.experiments import runner  # runner.py imports progress.py
            return runner
    """,
    )
    proc = lint_imports(tmp_path)
    assert proc.returncode == 1, shown(proc)
    out = " ".join(proc.stdout.split())
    for contract in (
        "Layers: entry points on top, the Node runtime and config at the bottom BROKEN",
        "Teams are independent of each other (shared code goes to teams/base.py, scripted.py or agents/) BROKEN",
        "No import cycles between the sibling packages and modules of any package BROKEN",
    ):
        assert contract in out, shown(proc)
    assert "pillagerbench.scenarios.mushroom_war -> pillagerbench.teams" in out, shown(proc)
    cycles = import_cycles(tmp_path)
    assert any({"pillagerbench.experiments.progress", "pillagerbench.experiments.runner"} <= set(c) for c in cycles)
    assert any({"pillagerbench.scenarios.mushroom_war", "pillagerbench.teams"} <= set(c) for c in cycles)


# --- JavaScript: what users install ------------------------------------------------------------------


def test_users_first_install_leaves_out_development_packages():
    users = ensure_node_modules(quiet=True)
    assert users == modules_dir() != modules_dir(dev=True)
    assert (users / "mineflayer").is_dir() and not (users / "eslint").exists()
