"""An experiment's run directory at its top: experiment.json (the experiment's name, its config, the
command's overrides and every series as a SeriesSpec), read back whichever version wrote it."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from pillagerbench.rundir.names import EXPERIMENT


def read_experiment(run_dir: str | Path) -> dict[str, Any]:
    """experiment.json as this version writes it, whichever version wrote it: the one place that knows
    its earlier versions. Before the experiment's design (round_robin, benchmark, ...) had its own
    word it was called `protocol`, in the experiment's config and in every series; `protocol` now
    means the LLM teams' loop only (a key of each series' config, left as it is)."""
    data = json.loads((Path(run_dir) / EXPERIMENT).read_text())
    for node in (data.get("experiment") or {}, *data.get("series", [])):
        if "design" not in node and "protocol" in node:
            node["design"] = node.pop("protocol")
    return data
