"""An experiment's run directory at its top: experiment.json (the experiment's name, its config, the
command's overrides and every series as a SeriesSpec's dict), read back whichever version wrote it."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ConfigDict

from pillagerbench.rundir.names import EXPERIMENT
from pillagerbench.rundir.whole import replace_json


class ExperimentFile(BaseModel):
    """experiment.json: written with its fields in this order, as it always was."""

    model_config = ConfigDict(extra="allow")

    name: str
    created: str | None = None
    experiment: dict[str, Any] = {}  # the experiment's config node (its design, teams, episodes, ...)
    overrides: list[str] = []  # the command's overrides
    series: list[dict[str, Any]] = []  # every series as SeriesSpec.to_dict() (rundir/series.py reads them)

    def to_dict(self) -> dict[str, Any]:
        """The file as it is written: the fields given, in their order (as every record's `to_dict`)."""
        return self.model_dump(exclude_unset=True)


def write_experiment_file(run_dir: str | Path, data: ExperimentFile) -> None:
    """experiment.json, replaced whole (a settled compare rewrites it: a kill leaves the old or the new)."""
    replace_json(Path(run_dir) / EXPERIMENT, data.to_dict(), indent=1)


def read_experiment(run_dir: str | Path) -> ExperimentFile:
    """experiment.json as this version writes it, whichever version wrote it: the one place that knows
    its earlier versions. Before the experiment's design (round_robin, benchmark, ...) had its own
    word it was called `protocol`, in the experiment's config and in every series; `protocol` now
    means the LLM teams' loop only (a key of each series' config, left as it is)."""
    data = json.loads((Path(run_dir) / EXPERIMENT).read_text())
    for node in (data.get("experiment") or {}, *data.get("series", [])):
        if "design" not in node and "protocol" in node:
            node["design"] = node.pop("protocol")
    return ExperimentFile.model_validate(data)
