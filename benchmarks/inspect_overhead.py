"""What Inspect adds per episode (issue 39): the same episodes played by `inspect eval
pillagerbench/mushroom_war` and by `pillagerbench run llm=inspect` (cot against passive, Inspect's mock
model answering both), alternately; prints JSON: wall time and peak memory (the whole process tree:
Python, the arena server, the bots) per episode of each, Inspect's overhead in %, and the log's size
per episode. Target: overhead ≤ 5 %.

    python benchmarks/inspect_overhead.py [--episodes 3] [--length 30] [--rounds 2]

The mock model counts tokens offline (tests/inspect_tasks/offline), as in the tests.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import psutil

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
ENV = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT / "tests/inspect_tasks/offline"), str(ROOT)])}


def measure(command: list[str], cwd: Path) -> tuple[float, float]:
    """Wall seconds and the peak RSS (MB) of the process and all its children, polled every 0.2 s."""
    t0 = time.perf_counter()
    proc = subprocess.Popen(command, cwd=cwd, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    root, peak = psutil.Process(proc.pid), 0
    while proc.poll() is None:
        try:
            tree = [root, *root.children(recursive=True)]
            peak = max(peak, sum(p.memory_info().rss for p in tree if p.is_running()))
        except psutil.Error:
            pass
        time.sleep(0.2)
    wall = time.perf_counter() - t0
    if proc.returncode:
        raise SystemExit(f"{command[0]} exited {proc.returncode}")
    return wall, peak / 2**20


def commands(work: Path, episodes: int, length: int, i: int) -> dict[str, list[str]]:
    return {
        "inspect": [
            str(BIN / "inspect"), "eval", "pillagerbench/mushroom_war", "--model", "mockllm/model",
            "-T", "opponents=passive", "-T", f"episodes={episodes}", "-T", f"episode_length={length}",
            "-T", f"run_dir={work / f'inspect_{i}'}", "--log-dir", str(work / f"logs_{i}"), "--display", "none",
        ],
        "pillagerbench": [
            str(BIN / "pillagerbench"), "run", "red=cot", "blue=passive", "llm=inspect", "llm.model=mockllm/model",
            "llm.preflight=false", f"episodes={episodes}", f"episode_length={length}",
            f"run_dir={work / f'run_{i}'}", "display=plain",
        ],
    }  # fmt: skip


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--episodes", type=int, default=3)
    ap.add_argument("--length", type=int, default=30)
    ap.add_argument("--rounds", type=int, default=2)
    a = ap.parse_args()
    results: dict[str, list[tuple[float, float]]] = {"inspect": [], "pillagerbench": []}
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for i in range(a.rounds):
            order = list(commands(work, a.episodes, a.length, i).items())
            for name, command in order if i % 2 == 0 else order[::-1]:  # alternate who goes first
                results[name].append(measure(command, work))
        logs = [p.stat().st_size for p in work.glob("logs_*/*.eval")]
        episodes = {
            name: sum(len(f.read_text().splitlines()) for d in work.glob(pattern) for f in d.rglob("episodes.jsonl"))
            for name, pattern in (("inspect", "inspect_*"), ("pillagerbench", "run_*"))
        }
    per = {n: statistics.median(w for w, _ in r) / a.episodes for n, r in results.items()}
    mem = {n: max(m for _, m in r) for n, r in results.items()}
    print(
        json.dumps(
            {
                "episodes": a.episodes,
                "episode_length_s": a.length,
                "rounds": a.rounds,
                "wall_s_per_episode": {n: round(v, 2) for n, v in per.items()},
                "wall_overhead_pct": round(100 * (per["inspect"] / per["pillagerbench"] - 1), 1),
                "peak_rss_mb": {n: round(v) for n, v in mem.items()},
                "rss_overhead_pct": round(100 * (mem["inspect"] / mem["pillagerbench"] - 1), 1),
                "eval_log_kb_per_episode": round(statistics.mean(logs) / 1024 / a.episodes, 1) if logs else None,
                "episodes_recorded": episodes,
            },
            indent=1,
        )
    )


if __name__ == "__main__":
    main()
