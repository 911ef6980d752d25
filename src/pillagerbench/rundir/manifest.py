"""The manifest of a run directory (`manifest.json`): config, versions, seed, git revision, suite and
the rules differing from the suite's defaults (suite/conditions.py).

Written by every series (experiments/series.py): an experiment's, and the one series of a plain
`pillagerbench run`; the experiment's own top-level manifest uses `git_revision` too.
"""

from __future__ import annotations

import platform
import subprocess
import time
from pathlib import Path
from typing import Any

from pillagerbench import __version__
from pillagerbench.config.schema import RunConfig
from pillagerbench.rundir import Manifest, RunDir, ScenarioStamp
from pillagerbench.suite.conditions import conditions_of
from pillagerbench.suite.version import current


def git_revision() -> str | None:
    try:
        return (
            subprocess.run(
                ["git", "rev-parse", "HEAD"], capture_output=True, text=True, timeout=5, cwd=Path(__file__).parent
            ).stdout.strip()
            or None
        )
    except (OSError, subprocess.SubprocessError):
        return None


def write_manifest(run_dir: Path, cfg: RunConfig, scenario: Any) -> None:
    """`run_dir/manifest.json` for one match; `scenario` is the Scenario played (key, title, version)."""
    from pillagerbench.host.node import node_binary

    node = subprocess.run([str(node_binary()), "--version"], capture_output=True, text=True).stdout.strip()
    manifest = Manifest(
        created=time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        config=cfg.stored(),
        scenario=ScenarioStamp(key=scenario.key, title=scenario.title, version=scenario.version),
        versions={
            "pillagerbench": __version__,
            "python": platform.python_version(),
            "node": node,
            "minecraft": "1.16.5",
        },
        seed=cfg.seed,
        git_revision=git_revision(),
        suite=current(),
        conditions=conditions_of(cfg.select, scenario.key),
    )
    RunDir(run_dir).write_manifest(manifest)
