"""The `pillagerbench` command as the tests run it: to the end (`run_cli`) or in the background in
its own session, so a test can kill it and everything it started (`start_cli`, `kill_run`)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

import psutil

COMMAND = [sys.executable, "-m", "pillagerbench.cli"]


def run_cli(cwd: Path, *args: str, env: dict | None = None, timeout: float = 120) -> subprocess.CompletedProcess:
    """Run to the end with output captured; no provider key leaks in from the caller's environment."""
    environment = {k: v for k, v in os.environ.items() if k != "OPENAI_API_KEY"}
    environment.update(env or {})
    return subprocess.run([*COMMAND, *args], cwd=cwd, capture_output=True, text=True, timeout=timeout, env=environment)


def start_cli(*args: str, **kw) -> subprocess.Popen:
    """Start in the background, stdout and stderr merged, in a session of its own."""
    return subprocess.Popen(
        [*COMMAND, *args], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True, **kw
    )


def kill_run(proc: subprocess.Popen) -> None:
    """SIGKILL a command started by `start_cli` and everything it started (its session), as a crash
    would; fails when a process outlives it."""
    children = psutil.Process(proc.pid).children(recursive=True)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    _, alive = psutil.wait_procs(children, timeout=15)
    assert not alive, f"processes outlived the killed run: {[p.pid for p in alive]}"


def refused_in_process(monkeypatch, capsys, cwd: Path, *argv: str, lines: int = 1) -> list[str]:
    """`cli.main(argv)` in-process (what `python -m pillagerbench.cli` exits with), in `cwd` and without a
    provider key, as `run_cli` runs the command, refuses: exit 2, `lines` lines on stderr, nothing on
    stdout, no traceback, no run directory in `cwd`. Returns those lines. (Imports of the command cost a
    subprocess seconds; tests/test_cli_errors.py checks the refusal end to end through the real command.)"""
    from pillagerbench.cli import commands as cli

    monkeypatch.chdir(cwd)
    monkeypatch.delenv("OPENAI_API_KEY", raising=False)
    code = cli.main(list(argv))
    out, err = capsys.readouterr()
    assert code == 2, (code, out, err)
    said = err.strip().splitlines()
    assert len(said) == lines and out == "", err
    assert "Traceback" not in err and not (cwd / "runs").exists(), err
    return said
