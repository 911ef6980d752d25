"""A run directory's manifest.json as a model: what was played (the config, the scenario), with what
(versions, git revision, suite) and under which rules (conditions). A series' manifest has every field;
an experiment's top-level one names the experiment and has no scenario, seed or conditions. Written with
the fields that were given, in this order, so the file is as it always was; a manifest of an earlier
version reads with what it has (unknown keys kept)."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict

from pillagerbench.suite.version import UNVERSIONED


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

    def to_json(self) -> dict[str, Any]:
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
