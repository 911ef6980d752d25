"""The recording format: every line of a recorded episode matches the schema, and the schema file
in docs/ is the one the code generates."""

from __future__ import annotations

import gzip
import json
from pathlib import Path

from pillagerbench.replay.schema import RECORD, json_schema

ROOT = Path(__file__).resolve().parents[2]
FIXTURE = Path(__file__).with_name("fixtures") / "episode_000" / "replay.jsonl.gz"


def test_every_recorded_line_matches_the_schema():
    kinds = set()
    with gzip.open(FIXTURE) as f:
        for line in f:
            record = RECORD.validate_python(json.loads(line))
            kinds.add(record.type)
    assert {
        "header",
        "blocks",
        "frame",
        "blocks_changed",
        "item",
        "item_gone",
        "event",
        "score",
        "program",
        "end",
    } <= kinds


def test_the_documented_schema_is_the_generated_one():
    documented = json.loads((ROOT / "docs" / "replays.schema.json").read_text())
    assert documented == json_schema(), "regenerate docs/replays.schema.json (see docs/replays.md)"
