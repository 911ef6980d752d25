"""The Inspect run's directory as one experiment directory (rundir/): experiment.json at its root lists
every series played so far, each epoch of a sample its own series (`<series id>_epoch<k>` under
series/), so `pillagerbench report ROOT` (and export, verify) read the whole Inspect run, and each
series directory is a run directory of its own as well.
"""

from __future__ import annotations

import dataclasses
import time
from pathlib import Path

from pillagerbench.rundir import ExperimentFile, RunDir, SeriesSpec, read_experiment, write_experiment_file


def add_series(root: Path, spec: SeriesSpec, task: str) -> tuple[SeriesSpec, Path]:
    """The epoch's series (named with its epoch) listed in the root's experiment.json, and its directory.
    Called from the solver on the evaluation's one event loop: no other sample writes in between."""
    rundir = RunDir(root)
    root.mkdir(parents=True, exist_ok=True)
    if rundir.is_experiment():
        data = read_experiment(root)
    else:
        data = ExperimentFile(
            name=f"inspect_{task}",
            created=time.strftime("%Y-%m-%dT%H:%M:%S%z"),
            experiment={"name": f"inspect_{task}", "design": spec.design},
        )
    if spec.id not in {s["id"] for s in data.series}:
        data.series = [*data.series, {**spec.to_dict(), "index": len(data.series)}]
        write_experiment_file(root, data)
    return dataclasses.replace(spec, index=len(data.series) - 1), rundir.series_dir(spec.id)
