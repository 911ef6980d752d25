"""live.json, the episode a series is playing, is written and read as `Live` (rundir/live.py), with the
keys it always had; an absent or half-written one reads as None."""

from __future__ import annotations

import json

from pillagerbench.rundir import Live, RunDir


def test_live_json_is_written_and_read_typed(tmp_path):
    rundir = RunDir(tmp_path)
    assert rundir.read_live() is None
    rundir.write_live(Live.of({"episode": 2, "t": 5, "length": 60.0, "red": 3.0, "blue": 1.0}))
    assert set(json.loads(rundir.live_path.read_text())) == {"episode", "t", "length", "red", "blue", "ts"}
    live = rundir.read_live()
    assert live is not None and (live.episode, live.t, live.length, live.red, live.blue) == (2, 5, 60.0, 3.0, 1.0)
    assert live.ts > 0
    rundir.live_path.write_text('{"episode": 1, "t"')  # being replaced as it is read
    assert rundir.read_live() is None
