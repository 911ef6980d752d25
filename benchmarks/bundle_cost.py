"""Results bundle benchmark (issue 32): the size of a bundle of a 150-episode run with replays, and the
command lines whose time to measure (export and verify, whole processes).

The run is fabricated: `tests.metrics.fake_runs.write_run` writes 150 episodes of 120 s (121-point
timelines), each given the files of a real episode (tests/experiments/fixtures/run_6198d49, 5 s)
with its events and world log repeated 24 times (5 s -> 120 s), and a replay of 37 KB (a 120 s
Mushroom War recording, docs/replays.md) of random bytes: a recording is gzip, which does not compress
again, and random bytes do not either.

    python benchmarks/bundle_cost.py make DIR          # write the run to DIR/run; print its size
    python benchmarks/bundle_cost.py size DIR          # export and verify once; print sizes and seconds
then time each command as a whole process, e.g. with /usr/bin/time -v:
    pillagerbench export DIR/run --out DIR/run.tar.gz --replays
    pillagerbench verify DIR/run.tar.gz
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from pillagerbench.rundir import RunDir
from tests.metrics.fake_runs import write_run

ROOT = Path(__file__).resolve().parents[1]

EPISODES, LENGTH, REPEAT, REPLAY_BYTES = 150, 120, 24, 37_000
REAL = RunDir(next((ROOT / "tests/experiments/fixtures/run_6198d49/series").iterdir())).episode(0)
TEXT = ("chat.txt", "game_master.json", "world_events.jsonl")


def make(out: Path) -> Path:
    scores = [(float(i % 7), float(20 + i % 5)) for i in range(EPISODES)]
    run = write_run(out / "run", "mushroom_war", "do_nothing", "passive", scores, length=LENGTH)
    for i in range(EPISODES):
        ep = RunDir(run).episode(i)
        for name in TEXT:
            (ep / name).write_text((REAL / name).read_text() * (REPEAT if name.endswith(".jsonl") else 1))
        for folder in ("events", "red", "blue"):
            (ep / folder).mkdir(exist_ok=True)
            for f in (REAL / folder).glob("*"):
                (ep / folder / f.name).write_text(f.read_text() * REPEAT)
        (ep / "replay.jsonl.gz").write_bytes(os.urandom(REPLAY_BYTES))
    return run


def size(path: Path) -> int:
    return sum(p.stat().st_size for p in path.rglob("*") if p.is_file()) if path.is_dir() else path.stat().st_size


def cli(*args: str) -> float:
    t = time.monotonic()
    subprocess.run([sys.executable, "-m", "pillagerbench.cli", *args], check=True, capture_output=True)
    return round(time.monotonic() - t, 2)


def main(argv: list[str]) -> int:
    command, out = argv[0], Path(argv[1])
    if command == "make":
        shutil.rmtree(out / "run", ignore_errors=True)
        run = make(out)
        print(json.dumps({"run": str(run), "episodes": EPISODES, "run_bytes": size(run)}))
        return 0
    run, bundle = out / "run", out / "run.tar.gz"
    bundle.unlink(missing_ok=True)
    seconds = {"export": cli("export", str(run), "--out", str(bundle), "--replays")}
    seconds["verify"] = cli("verify", str(bundle))
    plain = out / "run_no_replays.tar.gz"
    plain.unlink(missing_ok=True)
    cli("export", str(run), "--out", str(plain))
    sizes = {"run_bytes": size(run), "bundle_bytes": size(bundle), "bundle_without_replays_bytes": size(plain)}
    print(json.dumps({"episodes": EPISODES, **sizes, "seconds_once": seconds}))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
