"""What checking a bundle when it is read costs (issue 37 item 6): `pillagerbench report BUNDLE` of a
150-episode bundle with its checks (the default) against the same command with --no-verify.

The run is benchmarks/bundle_cost.py's fabricated one (150 episodes of 120 s, each with a real
episode's files scaled to 120 s and a 37 KB replay), exported with its replays: the checks hash every
file, so the replays are in. Both commands write tables only (--no-replays): the replay pages cost the
same either way.

    python benchmarks/bundle_verify.py make DIR        # DIR/run and DIR/run.tar.gz; prints their sizes
    python benchmarks/bundle_verify.py time DIR [N]    # N (default 5) runs of each, in turn; medians of
                                                       # wall and CPU seconds (CPU: steadier on a busy machine)
    python benchmarks/bundle_verify.py check DIR       # the checks alone, in one process, once unpacked
or time the two whole processes with any tool, e.g. /usr/bin/time -v:
    pillagerbench report DIR/run.tar.gz --no-replays --out DIR/checked
    pillagerbench report DIR/run.tar.gz --no-replays --out DIR/unchecked --no-verify
"""

from __future__ import annotations

import json
import resource
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bundle_cost import EPISODES, make, size  # the same fabricated run

COMMANDS = {
    "checked": ["--no-replays", "--out", "{dir}/checked"],
    "unchecked": ["--no-replays", "--out", "{dir}/unchecked", "--no-verify"],
}


def _cpu() -> float:
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    return used.ru_utime + used.ru_stime


def report(out: Path, how: str) -> tuple[float, float]:
    """(wall, CPU) seconds of one whole `pillagerbench report` process."""
    args = [a.format(dir=out) for a in COMMANDS[how]]
    t, cpu = time.monotonic(), _cpu()
    subprocess.run(
        [sys.executable, "-m", "pillagerbench.cli", "report", str(out / "run.tar.gz"), *args],
        check=True,
        capture_output=True,
    )
    return time.monotonic() - t, _cpu() - cpu


def check(bundle: Path) -> int:
    """The checks alone, in this process, after the unpacking that reading the bundle does anyway."""
    from pillagerbench.metrics.verified import bundle_problems
    from pillagerbench.rundir.bundle import unpack

    unpack(bundle)
    wall, cpu = time.monotonic(), time.process_time()
    problems = bundle_problems(bundle)[0]
    wall, cpu = time.monotonic() - wall, time.process_time() - cpu
    print(
        json.dumps({"episodes": EPISODES, "problems": len(problems), "wall_s": round(wall, 3), "cpu_s": round(cpu, 3)})
    )
    return 0


def main(argv: list[str]) -> int:
    command, out = argv[0], Path(argv[1])
    if command == "make":
        shutil.rmtree(out / "run", ignore_errors=True)
        run, bundle = make(out), out / "run.tar.gz"
        bundle.unlink(missing_ok=True)
        subprocess.run(
            [sys.executable, "-m", "pillagerbench.cli", "export", str(run), "--out", str(bundle), "--replays"],
            check=True,
            capture_output=True,
        )
        print(json.dumps({"episodes": EPISODES, "run_bytes": size(run), "bundle_bytes": size(bundle)}))
        return 0
    if command == "check":
        return check(out / "run.tar.gz")
    runs = int(argv[2]) if len(argv) > 2 else 5
    seconds: dict[str, list[tuple[float, float]]] = {how: [] for how in COMMANDS}
    for _ in range(runs):  # in turn, so a drift of the machine's speed falls on both
        for how in COMMANDS:
            seconds[how].append(report(out, how))
    result: dict = {"episodes": EPISODES, "runs": runs}
    for i, kind in enumerate(("wall", "cpu")):
        medians = {how: round(statistics.median(s[i] for s in got), 2) for how, got in seconds.items()}
        result[f"median_{kind}_s"] = medians
        result[f"verification_adds_{kind}_s"] = round(medians["checked"] - medians["unchecked"], 2)
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
