"""A day of play leaks nothing (issue 55, item 5): many lockstep episodes on one warm server, and what
each process holds over them. Writes samples.jsonl (as it goes), summary.json and day_of_play.png into
--out, and prints the summary.

    python benchmarks/day_of_play.py [--episodes 500] [--length 15] [--out DIR]
        [--red aggressive --blue slimy] [--every 5]
    python benchmarks/day_of_play.py --report DIR     # the summary and figure again from DIR's samples
    python benchmarks/day_of_play.py --league [--wall 3600] [--length 15] [--parallel 1] [--out DIR]

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
least-squares slope over the same span in MB per 100 episodes; a process restarted (a starved bot) also
its own growth since (`since_restart`: its warm-up the first 20 % of the episodes after the restart),
which is the one the verdict reads. Target: under 5 % growth.

--league: a league of the built-in teams played for --wall seconds of wall time, as a user plays one
(`pillagerbench league DIR init confidence=0.99999`, then `pillagerbench league DIR play
budget.episodes=100000 clock=lockstep episode_length=L parallel=P display=plain`, stopped by Ctrl-C at
the deadline; played again if it settles first). One Python process plays every round; each match is a
series with its own server and bots, which end with it. So the kinds sampled are `python` (the league's
process: RSS and descriptors), `server` and `bot` (per process: the mean RSS and descriptors of those
alive, and `n`, how many are alive: a process left behind by a finished series shows there), against
the episodes finished in every round.
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


def sample(runner: psutil.Process, league: bool = False) -> dict[str, dict]:
    """RSS (MB) and open descriptors of each process of the run, by kind (a kind seen twice, a bot
    restarted while the old one ends: summed). `league`: kinds `python`, `server`, `bot`, each the
    mean of its processes alive, with their number `n`."""
    out: dict[str, dict] = {}
    try:
        procs = [runner, *runner.children(recursive=True)]
    except psutil.Error:
        return out
    for proc in procs:
        kind = kind_of(proc, runner.pid)
        if kind is None:
            continue
        if league:
            kind = kind.split(":")[0]
        try:
            with proc.oneshot():
                rss, fds = proc.memory_info().rss / 2**20, proc.num_fds()
        except psutil.Error:
            continue
        seen = out.setdefault(kind, {"rss_mb": 0.0, "fds": 0, "pids": []})
        seen["rss_mb"] = round(seen["rss_mb"] + rss, 1)
        seen["fds"] += fds
        seen["pids"].append(proc.pid)
    if league:
        for seen in out.values():
            n = seen["n"] = len(seen.pop("pids"))
            seen["rss_mb"], seen["fds"] = round(seen["rss_mb"] / n, 1), round(seen["fds"] / n, 1)
    return out


def episode_files(run_dir: Path) -> list[Path]:
    """The run's episodes.jsonl; for a league, every round's series' files in order."""
    if (run_dir / "league.yaml").exists():
        return sorted((run_dir / "matches").glob("round_*/series/*/episodes.jsonl"))
    return [run_dir / "episodes.jsonl"]


def episodes_done(run_dir: Path) -> int:
    n = 0
    for path in episode_files(run_dir):
        try:
            with open(path, "rb") as fh:
                n += sum(1 for _ in fh)
        except FileNotFoundError:
            pass
    return n


def records_of(run_dir: Path) -> list[dict]:
    """Every episode record of the run (a league's round by round, each round's series one after another)."""
    return [r for path in episode_files(run_dir) if path.exists() for r in read_jsonl(path)]


def play(a: argparse.Namespace, out: Path) -> int:
    """The run, sampled until it ends; its exit code."""
    run_dir = out / "run"
    cmd = [
        *CLI, "run", "clock=lockstep", f"red={a.red}", f"blue={a.blue}", f"episodes={a.episodes}",
        f"episode_length={a.length}", f"run_dir={run_dir}", "display=plain",
    ]  # fmt: skip
    (out / "command.txt").write_text(" ".join(cmd) + "\n")
    return sampled(cmd, out, run_dir, a.every, time.monotonic(), None)


def sampled(cmd: list[str], out: Path, run_dir: Path, every: float, t0: float, deadline: float | None) -> int:
    """`cmd` played and sampled until it ends, or until `deadline` (monotonic) when it is stopped by
    Ctrl-C, as a user stops a run; its exit code."""
    league = deadline is not None
    with open(out / "run.log", "ab") as log, open(out / SAMPLES, "a") as samples:
        proc = subprocess.Popen(cmd, cwd=ROOT, stdout=log, stderr=subprocess.STDOUT)
        runner = psutil.Process(proc.pid)
        try:
            while proc.poll() is None and (deadline is None or time.monotonic() < deadline):
                line = {"t": round(time.monotonic() - t0, 1), "episodes": episodes_done(run_dir)}
                line["load"] = round(psutil.getloadavg()[0], 2)
                samples.write(json.dumps({**line, "procs": sample(runner, league)}) + "\n")
                samples.flush()
                time.sleep(every)
        finally:  # stopped (Ctrl-C, kill, the deadline): the run stops too, as its own Ctrl-C would
            if proc.poll() is None:
                proc.send_signal(signal.SIGINT)
                try:
                    proc.wait(timeout=120)
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait()
    return proc.returncode


def play_league(a: argparse.Namespace, out: Path) -> int:
    """A league of the built-in teams played for a.wall seconds (see the module's docstring)."""
    league_dir = out / "run"
    confidence = 0.99999  # far from settled: the league keeps scheduling for the whole hour
    init = [*CLI, "league", str(league_dir), "init", f"confidence={confidence}"]
    subprocess.run(init, cwd=ROOT, check=True, stdout=subprocess.DEVNULL)
    game = [f"clock={a.clock}", f"episode_length={a.length}", f"parallel={a.parallel}", "display=plain"]
    play_cmd = [*CLI, "league", str(league_dir), "play", "budget.episodes=100000", *game]
    (out / "command.txt").write_text(" ".join(play_cmd) + f"  # for {a.wall:g} s of wall time\n")
    t0 = time.monotonic()
    deadline, code, again = t0 + a.wall, 0, []
    while time.monotonic() < deadline - 60 and code == 0:  # settled early: played on, closer to 1
        code = sampled([*play_cmd, *again], out, league_dir, a.every, t0, deadline)
        confidence = 1 - (1 - confidence) / 10
        again = [f"confidence={confidence}"]
    return 0 if code in (0, -signal.SIGINT, 130) else code


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


def growth(samples: list[dict], kind: str, field: str, episodes: int, start: float = 0) -> dict:
    """From the end of warm-up (WARM_UP of the episodes after `start`) to the end."""
    span = episodes - start
    warm, half = max(1.0, start + span * WARM_UP), max(1.0, span * WINDOW / 2)
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


def last_start(samples: list[dict], kind: str) -> int:
    """The episode count when the last process of `kind` started (a restart), as the samples saw it."""
    seen: set[int] = set()
    start = 0
    for s in samples:
        pids = set(s["procs"].get(kind, {}).get("pids", []))
        if seen and pids - seen:
            start = s["episodes"]
        seen |= pids
    return start


def rss_growth(proc: dict) -> float | None:
    """A kind's RSS growth: the live process's own since its restart, if it was restarted."""
    return (proc.get("since_restart") or proc["rss_mb"])["growth_pct"]


def summarize(out: Path) -> dict:
    samples = read_jsonl(out / SAMPLES)
    records = records_of(out / "run")
    n = len(records)
    kinds = sorted({k for s in samples for k in s["procs"]}, key=lambda k: (k != "python", k != "server", k))
    procs = {k: {f: growth(samples, k, f, n) for f, _ in FIELDS} for k in kinds}
    for k in kinds:  # a process restarted (a bot that died or did not stop) starts its RSS afresh
        if (out / "run" / "league.yaml").exists():  # processes come and go with the series: how many at most
            procs[k]["most_alive"] = max(s["procs"].get(k, {}).get("n", 0) for s in samples)
            procs[k]["after_last_sample"] = samples[-1]["procs"].get(k, {}).get("n", 0)
            continue
        procs[k]["restarts"] = len({p for s in samples for p in s["procs"].get(k, {}).get("pids", [])}) - 1
        if procs[k]["restarts"] and (since := last_start(samples, k)) < n:  # the live process's own growth
            procs[k]["since_restart"] = {"episode": since, **growth(samples, k, "rss_mb", n, since)}
    worst = max((rss_growth(p) or 0.0 for p in procs.values()), default=0.0)
    eps = per_episode(records)
    return {
        "command": (out / "command.txt").read_text().strip().splitlines()[0],
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
    series = per_episode(records_of(out / "run"))["series"]
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
    ap.add_argument("--league", action="store_true", help="a league of the built-in teams for --wall seconds")
    ap.add_argument("--wall", type=float, default=3600, help="--league: seconds of wall time (default an hour)")
    ap.add_argument("--parallel", type=int, default=1, help="--league: matches played at once")
    ap.add_argument("--clock", default="lockstep", choices=("lockstep", "real"), help="--league: the game clock")
    a = ap.parse_args()
    if a.report:
        print(json.dumps(report(a.report), indent=1))
        return 0
    out = a.out or Path(f"/tmp/day_of_play_{'league_' if a.league else ''}{time.strftime('%Y%m%d_%H%M%S')}")
    out.mkdir(parents=True, exist_ok=True)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))  # kill PID: the run is stopped first (play)
    code = play_league(a, out) if a.league else play(a, out)
    print(json.dumps(report(out), indent=1))
    return code


if __name__ == "__main__":
    sys.exit(main())
