"""The `pillagerbench` command as the tests run it: to the end (`run_cli`) or in the background in
its own session, so a test can kill it and everything it started (`start_cli`)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

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
