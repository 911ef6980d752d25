"""live.json, the episode a series is playing, is written and read as `Live` (rundir/live.py), with the
keys it always had; an absent or half-written one reads as None."""

from __future__ import annotations

import json

from pillagerbench.rundir import Live, LiveWriter, RunDir


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


def test_live_json_is_written_at_most_twice_a_wall_second_and_at_each_episodes_start_and_end():
    written, clock = [], [0.0]
    live = LiveWriter(written.append, every_s=0.5, now=lambda: clock[0])
    for t in range(60):  # a lockstep game: 60 game seconds in 0.59 s of wall time
        live({"episode": 0, "t": t, "length": 60.0})
        clock[0] += 0.01
    live({"episode": 0, "t": 60, "length": 60.0})  # the whistle
    live({"episode": 1, "t": 0, "length": 60.0})  # the next episode begins
    assert [(w.episode, w.t) for w in written] == [(0, 0), (0, 50), (0, 60), (1, 0)]
