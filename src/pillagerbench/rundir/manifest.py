"""A run directory's manifest.json: what was played (the config, the scenario), with what (versions, git
revision, suite) and under which rules (conditions, the rules differing from the suite's defaults:
suite/conditions.py). A series' manifest has every field (`match_manifest`: every series writes one, an
experiment's and the one series of a plain `pillagerbench run`); an experiment's top-level one names the
experiment and has no scenario, seed or conditions. Written with the fields that were given, in this order,
so the file is as it always was; a manifest of an earlier version reads with what it has (unknown keys kept).
"""

from __future__ import annotations

import platform
import subprocess
import time
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ConfigDict

from pillagerbench import __version__
from pillagerbench.config.schema import RunConfig, RunnerConfig
from pillagerbench.suite.conditions import conditions_of
from pillagerbench.suite.version import UNVERSIONED, current


class ScenarioStamp(BaseModel):
    model_config = ConfigDict(extra="allow")

    key: str | None = None
    title: str | None = None
    version: str | int | float | None = None


class Manifest(BaseModel):
    model_config = ConfigDict(extra="allow")

    created: str | None = None
    config: dict[str, Any] = {}  # the resolved configuration
    scenario: ScenarioStamp | None = None
    versions: dict[str, Any] = {}  # pillagerbench, python, node, minecraft
    seed: int | None = None
    git_revision: str | None = None
    suite: dict[str, Any] | None = None  # suite.current(): name, sha256, label
    conditions: dict[str, Any] | None = None  # the rules differing from the suite's (suite/conditions.py)
    experiment: str | None = None  # an experiment's top-level manifest: its name

    def to_dict(self) -> dict[str, Any]:
        """The fields given, as written."""
        return self.model_dump(exclude_unset=True)

    @property
    def scenario_version(self) -> str:
        """The scenario's version ("?" when the manifest does not say)."""
        version = self.scenario.version if self.scenario else None
        return "?" if version is None else str(version)

    @property
    def suite_label(self) -> str:
        """The suite it was played under ("unversioned" before suite versions)."""
        return str((self.suite or {}).get("label") or UNVERSIONED)


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


def stored(config: RunnerConfig) -> dict[str, Any]:
    """A configuration as a run directory's records write it: a series' whole (its manifest.json, its
    entry in experiment.json) as composed; an experiment's (its manifest.json) with the keys it was given.
    The one writer of a stored configuration; `Manifest.config` and `RunConfig.of` read it back."""
    return config.stored()


def experiment_manifest(config: RunnerConfig, created: str) -> Manifest:
    """The top-level manifest of an experiment (a league round's, a compare's too): its configuration,
    what played it and its name; no scenario, seed or conditions (each series' manifest has those)."""
    assert config.experiment is not None, "an experiment's configuration names its experiment"
    return Manifest(
        created=created,
        config=stored(config),
        versions={"pillagerbench": __version__},
        git_revision=git_revision(),
        suite=current(),
        experiment=config.experiment.name,
    )


def match_manifest(cfg: RunConfig, scenario: Any) -> Manifest:
    """The manifest of one match (a series); `scenario` is the Scenario played (key, title, version)."""
    from pillagerbench.host.node import node_binary

    node = subprocess.run([str(node_binary()), "--version"], capture_output=True, text=True).stdout.strip()
    return Manifest(
        created=time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        config=stored(cfg),
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
