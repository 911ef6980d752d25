"""A JSON file of a run replaced whole: written beside it and renamed over it, so a kill leaves the old
file or the new one, never half of one (live.json, experiment.json, compare.json, outage.json,
manifest.json, episode.json)."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any


def replace_json(path: Path, data: Any, indent: int | None = None) -> None:
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(json.dumps(data, indent=indent, default=str))
    os.replace(tmp, path)
