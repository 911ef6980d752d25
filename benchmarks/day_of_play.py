"""A day of play leaks nothing (issue 55, item 5): many lockstep episodes on one warm server, and what
each process holds over them. Writes samples.jsonl (as it goes), summary.json and day_of_play.png into
--out, and prints the summary.

    python benchmarks/day_of_play.py [--episodes 500] [--length 15] [--out DIR]
        [--red aggressive --blue slimy] [--every 5]
    python benchmarks/day_of_play.py --report DIR     # the summary and figure again from DIR's samples

It runs `pillagerbench run clock=lockstep red=RED blue=BLUE episodes=N episode_length=L` in a
subprocess (a plain run is one series: one server and the same bot processes for every episode, a bot
restarted only when it dies) and samples every --every seconds, with psutil, each process of the run
told apart by its command line: the Python runner, the arena server's node (`server/main.js`) and
each bot's node (`bot/main.js`, named by the `username` in its settings): RSS and open file
descriptors. Per episode (episodes.jsonl): wall time and the lockstep tick's wall time, 1000 /
`server_tps` ms (the server's game ticks per wall second; on the lockstep clock each tick waits for
every bot, so this is the event-loop delay of the slowest of the node processes in each tick, the
closest figure the run already records; the bots' own `bot_lag` reads the game clock there).

The summary gives, per process kind, the RSS and descriptors at the end of warm-up (the episode at
20 % of the run, 100 of 500) and at the end, growth in % between them (the median of the samples
during the 5 % of episodes around each point, so one garbage collection does not decide it), and the
least-squares slope over the same span in MB per 100 episodes. Target: under 5 % growth.
"""

from __future__ import annotations

import argparse
import json
import signal
import subprocess
import sys
import time
from pathlib import Path
from statistics import median

import psutil

ROOT = Path(__file__).resolve().parents[1]
CLI = [sys.executable, "-m", "pillagerbench.cli"]
WARM_UP = 0.2  # the share of the run left out of the growth: loading, JIT, caches filling
WINDOW = 0.05  # the share of the run whose samples give a point's value (median)
TARGET_PCT = 5.0
SAMPLES, SUMMARY, FIGURE = "samples.jsonl", "summary.json", "day_of_play.png"
FIELDS = (("rss_mb", "RSS (MB)"), ("fds", "open file descriptors"))


def kind_of(proc: psutil.Process, runner: int) -> str | None:
    """The process kind: `python` (the runner), `server`, `bot:NAME`; None for anything else."""
    if proc.pid == runner:
        return "python"
    try:
        cmd = proc.cmdline()
    except psutil.Error:
        return None
    if any(part.endswith("server/main.js") for part in cmd):
        return "server"
    if any(part.endswith("bot/main.js") for part in cmd):
        try:
            return "bot:" + json.loads(cmd[-1])["username"]
        except (ValueError, KeyError, IndexError):
            return "bot:?"
    return None


def sample(runner: psutil.Process) -> dict[str, dict[str, float]]:
    """RSS (MB) and open descriptors of each process of the run, by kind (a kind seen twice, a bot
    restarted while the old one ends: summed)."""
    out: dict[str, dict[str, float]] = {}
    try:
        procs = [runner, *runner.children(recursive=True)]
    except psutil.Error:
        return out
    for proc in procs:
        kind = kind_of(proc, runner.pid)
        if kind is None:
            continue
        try:
            with proc.oneshot():
                rss, fds = proc.memory_info().rss / 2**20, proc.num_fds()
        except psutil.Error:
            continue
        seen = out.setdefault(kind, {"rss_mb": 0.0, "fds": 0, "pids": []})
        seen["rss_mb"] = round(seen["rss_mb"] + rss, 1)
        seen["fds"] += fds
        seen["pids"].append(proc.pid)
    return out


def episodes_done(run_dir: Path) -> int:
    try:
        with open(run_dir / "episodes.jsonl", "rb") as fh:
            return sum(1 for _ in fh)
    except FileNotFoundError:
        return 0


def play(a: argparse.Namespace, out: Path) -> int:
    """The run, sampled until it ends; its exit code."""
    run_dir = out / "run"
    cmd = [
        *CLI, "run", "clock=lockstep", f"red={a.red}", f"blue={a.blue}", f"episodes={a.episodes}",
        f"episode_length={a.length}", f"run_dir={run_dir}", "display=plain",
    ]  # fmt: skip
    (out / "command.txt").write_text(" ".join(cmd) + "\n")
    t0 = time.monotonic()
    with open(out / "run.log", "wb") as log, open(out / SAMPLES, "a") as samples:
        proc = subprocess.Popen(cmd, cwd=ROOT, stdout=log, stderr=subprocess.STDOUT)
        runner = psutil.Process(proc.pid)
        try:
            while proc.poll() is None:
                line = {"t": round(time.monotonic() - t0, 1), "episodes": episodes_done(run_dir)}
                line["load"] = round(psutil.getloadavg()[0], 2)
                samples.write(json.dumps({**line, "procs": sample(runner)}) + "\n")
                samples.flush()
                time.sleep(a.every)
        finally:  # stopped (Ctrl-C, kill): the run stops too, as its own Ctrl-C would (resume= finishes it)
            if proc.poll() is None:
                proc.send_signal(signal.SIGINT)
                proc.wait()
    return proc.returncode


def read_jsonl(path: Path) -> list[dict]:
    with open(path) as fh:
        return [json.loads(line) for line in fh if line.strip()]


def at(samples: list[dict], kind: str, field: str, episode: float, half: float) -> float | None:
    """The median of a kind's field over the samples taken while episodes episode ± half were played."""
    vals = [s["procs"][kind][field] for s in samples if abs(s["episodes"] - episode) <= half and kind in s["procs"]]
    return round(median(vals), 1) if vals else None


def slope_per_100(samples: list[dict], kind: str, field: str, start: float) -> float | None:
    """Least-squares slope of a kind's field against episodes played, from `start` on, per 100 episodes."""
    pts = [(s["episodes"], s["procs"][kind][field]) for s in samples if s["episodes"] >= start and kind in s["procs"]]
    if len(pts) < 2:
        return None
    mx, my = sum(x for x, _ in pts) / len(pts), sum(y for _, y in pts) / len(pts)
    var = sum((x - mx) ** 2 for x, _ in pts)
    return round(100 * sum((x - mx) * (y - my) for x, y in pts) / var, 2) if var else None


def growth(samples: list[dict], kind: str, field: str, episodes: int) -> dict:
    warm, half = max(1.0, episodes * WARM_UP), max(1.0, episodes * WINDOW / 2)
    first, last = at(samples, kind, field, warm, half), at(samples, kind, field, episodes - half, half)
    pct = round(100 * (last - first) / first, 1) if first and last is not None else None
    return {
        "warm": first,
        "end": last,
        "growth_pct": pct,
        "per_100_episodes": slope_per_100(samples, kind, field, warm),
    }


def per_episode(records: list[dict]) -> dict:
    """Wall time per episode and the lockstep tick's wall time, first and last fifths beside each other."""
    wall = [r.get("duration_s") or 0.0 for r in records]
    tick = [round(1000 / r["server_tps"], 2) if r.get("server_tps") else None for r in records]
    fifth = max(1, len(records) // 5)

    def mean(xs: list) -> float | None:
        xs = [x for x in xs if x is not None]
        return round(sum(xs) / len(xs), 3) if xs else None

    return {
        "episodes": len(records),
        "failed": sum(1 for r in records if r.get("status") != "ok"),
        "wall_s": {"first_fifth": mean(wall[fifth : 2 * fifth]), "last_fifth": mean(wall[-fifth:])},
        "tick_ms": {"first_fifth": mean(tick[fifth : 2 * fifth]), "last_fifth": mean(tick[-fifth:])},
        "series": {"wall_s": wall, "tick_ms": tick},
    }


def summarize(out: Path) -> dict:
    samples = read_jsonl(out / SAMPLES)
    records = read_jsonl(out / "run" / "episodes.jsonl")
    n = len(records)
    kinds = sorted({k for s in samples for k in s["procs"]}, key=lambda k: (k != "python", k != "server", k))
    procs = {k: {f: growth(samples, k, f, n) for f, _ in FIELDS} for k in kinds}
    for k in kinds:  # a process restarted (a bot that died or did not stop) starts its RSS afresh
        procs[k]["restarts"] = len({p for s in samples for p in s["procs"].get(k, {}).get("pids", [])}) - 1
    worst = max((p["rss_mb"]["growth_pct"] or 0.0 for p in procs.values()), default=0.0)
    eps = per_episode(records)
    return {
        "command": (out / "command.txt").read_text().strip(),
        "episodes": n,
        "wall_h": round(samples[-1]["t"] / 3600, 2) if samples else 0,
        "load_avg": {"min": min(s["load"] for s in samples), "max": max(s["load"] for s in samples)},
        "warm_up_episode": round(max(1.0, n * WARM_UP)),
        "processes": procs,
        "worst_rss_growth_pct": worst,
        "flat": worst < TARGET_PCT,
        **{k: v for k, v in eps.items() if k != "series"},
    }


def figure(out: Path, summary: dict) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    samples = read_jsonl(out / SAMPLES)
    series = per_episode(read_jsonl(out / "run" / "episodes.jsonl"))["series"]
    fig, axes = plt.subplots(2, 2, figsize=(12, 8), sharex=True)
    for ax, (field, label) in zip(axes[0], FIELDS, strict=True):
        for kind in summary["processes"]:
            pts = [(s["episodes"], s["procs"][kind][field]) for s in samples if kind in s["procs"]]
            ax.plot([x for x, _ in pts], [y for _, y in pts], label=kind, lw=1)
        ax.set_ylabel(label)
        ax.axvline(summary["warm_up_episode"], color="grey", ls=":", lw=1)
    axes[0][0].legend(fontsize=8)
    for ax, key, label in (
        (axes[1][0], "wall_s", "episode wall time (s)"),
        (axes[1][1], "tick_ms", "lockstep tick (ms wall)"),
    ):
        ax.plot(range(len(series[key])), series[key], ".", ms=2)
        ax.set_ylabel(label)
        ax.set_xlabel("episodes played")
        load = ax.twinx()  # the machine is shared: wall times follow its load
        load.plot([s["episodes"] for s in samples], [s["load"] for s in samples], color="grey", lw=0.6, alpha=0.6)
        load.set_ylabel("load average (1 min)", color="grey")
    fig.suptitle(f"{summary['command'].split(' run ', 1)[-1]}  ({summary['wall_h']} h)", fontsize=9)
    fig.tight_layout()
    fig.savefig(out / FIGURE, dpi=90)


def report(out: Path) -> dict:
    summary = summarize(out)
    (out / SUMMARY).write_text(json.dumps(summary, indent=1) + "\n")
    figure(out, summary)
    return summary


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--episodes", type=int, default=500)
    ap.add_argument("--length", type=float, default=15, help="game seconds per episode")
    ap.add_argument("--out", type=Path, help="output directory (default: a new one under /tmp)")
    ap.add_argument("--red", default="aggressive")
    ap.add_argument("--blue", default="slimy")
    ap.add_argument("--every", type=float, default=5, help="seconds between samples")
    ap.add_argument("--report", type=Path, metavar="DIR", help="only the summary and figure of a run in DIR")
    a = ap.parse_args()
    if a.report:
        print(json.dumps(report(a.report), indent=1))
        return 0
    out = a.out or Path(f"/tmp/day_of_play_{time.strftime('%Y%m%d_%H%M%S')}")
    out.mkdir(parents=True, exist_ok=True)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))  # kill PID: the run is stopped first (play)
    code = play(a, out)
    print(json.dumps(report(out), indent=1))
    return code


if __name__ == "__main__":
    sys.exit(main())
