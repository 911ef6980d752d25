"""Killed anywhere, nothing lost or doubled (issue 55, item 6): start a run in a subprocess (an
experiment, a `compare`, a league round; with a remote team, on Ray), SIGKILL one of its processes at a
seeded random moment (the runner, the arena server, a bot, or a remote team's server, which its owner
starts again), let the run handle a child's death or resume it after the runner's, then check the run
directories: every planned episode exactly once, every JSON and JSONL record whole, the report counting
what an unkilled run of the same spec plans, and the run exported as a results bundle that `verify`
passes and whose counts are the run's.

Shared by tests/experiments/test_kill_anywhere.py (a few seeds) and benchmarks/kill_anywhere.py (many).
"""

from __future__ import annotations

import json
import os
import random
import re
import signal
import subprocess
import tempfile
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path

import psutil

from tests.support.cli import run_cli, start_cli

ROOT = Path(__file__).resolve().parents[2]
KINDS = ("runner", "server", "bot")
MARKS = {"server": "js/server/main.js", "bot": "js/bot/main.js"}  # a child's kind by its command line
ORPHAN_WAIT_S = 10.0  # how long the runner's children get to leave by themselves after it died
SUITE_MOVED = re.compile(r"manifest\.json: says suite \S+, but \d+ episode\(s\) say suite ")
DOWN_S = 1.0  # how long a killed outside process (a remote team's server) stays down before its owner restarts it


def _nothing(root: Path, kind: str) -> psutil.Process | None:
    return None


@dataclass(frozen=True)
class Target:
    """A kind of run to kill: its commands, where its series directories are, and what it plans."""

    name: str
    span_s: float  # about an unkilled run's wall time on the development machine (where a kill lands)
    planned: int  # episodes an unkilled run uses (the kill's "after N records" is drawn below it)
    start: Callable[[Path], list[str]]  # the command (its first word the sub-command), in a fresh directory
    resume: Callable[[Path], list[str]]  # the command that finishes it after a kill
    series: str  # glob of its series directories under the directory
    runs: Callable[[Path], list[Path]]  # the run directories the report reads
    expected: Callable[[Path], dict[Path, int]]  # series directory -> episodes it must use (read after the run)
    prepare: Callable[[Path], None] = lambda root: None  # before the start (a league's init, a team's server)
    finished: Callable[[Path], list[str]] = lambda root: []  # what else an ended run must show (a compare's answer)
    kinds: tuple[str, ...] = KINDS  # the kinds of process a seed draws from
    # a process of a drawn kind that is not the runner's child (a remote team's server), and its restart
    outside: Callable[[Path, str], psutil.Process | None] = _nothing
    revive: Callable[[Path, str], None] = lambda root, kind: None
    cleanup: Callable[[Path], None] = lambda root: None  # after the run and its check (a team's server stopped)
    # command-line marks of processes not ours that may outlive a killed runner for a while (Ray's agents)
    lingering: tuple[str, ...] = ()


@dataclass
class Kill:
    """One seeded kill and what came of it."""

    seed: int
    target: str
    asked: str  # the kind of process drawn
    at_s: float | None = None  # kill this many seconds after the start, or
    after_records: int | None = None  # as soon as this many episodes are recorded
    killed: str = ""  # the kind actually killed ("none": the run ended first)
    moment: str = ""  # where the run stood: before episodes, mid-episode, between episodes, after the last
    records_at_kill: int = 0
    run_exit: int | None = None  # a child's kill: how the run ended by itself (None: killed, or hung)
    hung: bool = False  # after a child's kill the run did not end within its time
    orphans: list[str] = field(default_factory=list)  # the runner's children alive ORPHAN_WAIT_S after it died
    lingering: list[str] = field(default_factory=list)  # those of them the target lets linger (Target.lingering)
    resumed: bool = False
    resume_exit: int | None = None
    given_up: int = 0  # planned episodes given up after every try spoiled (a loaded machine's lag)
    wall_s: float = 0.0
    problems: list[str] = field(default_factory=list)
    output: str = ""  # the commands' output (for a failing test; left out of the benchmark's summary)

    def summary(self) -> dict:
        return {k: v for k, v in asdict(self).items() if k != "output"}


def draw(seed: int, target: Target) -> Kill:
    """The kill a seed gives: which kind of process, and when (a time within the run's span, or a
    count of recorded episodes)."""
    rng = random.Random(seed)
    kill = Kill(seed, target.name, rng.choice(target.kinds))
    if rng.random() < 0.5:
        kill.at_s = round(rng.uniform(0.1, 1.0) * target.span_s, 2)
    else:
        kill.after_records = rng.randrange(target.planned)
    return kill


# --- the run directories -------------------------------------------------------------------------------


def _lines(path: Path) -> list[str]:
    return path.read_text().splitlines() if path.exists() else []


def _parsed(text: str) -> dict | None:
    try:
        found = json.loads(text)
    except ValueError:
        return None
    return found if isinstance(found, dict) else None


def records(root: Path, target: Target) -> int:
    """Episode lines recorded so far, every series."""
    return sum(len(_lines(d / "episodes.jsonl")) for d in root.glob(target.series))


def moment(root: Path, target: Target, alive: bool) -> str:
    """Where the run stands: no episode recorded or played yet, one in play, between two, or done."""
    series = list(root.glob(target.series))
    if any((d / "live.json").exists() for d in series):
        return "mid-episode"
    done = records(root, target)
    if not done:
        return "before the first episode"
    return "between episodes" if alive and done < target.planned else "after the last episode"


def whole_records(root: Path) -> list[str]:
    """Every JSON and JSONL file under `root` that does not parse whole, each line of a JSONL file on its
    own (discarded/ holds what a resume moved aside, torn on purpose; a report's output is not the run's)."""
    bad = []
    for path in sorted(root.rglob("*.json*")):
        if "discarded" in path.parts or "report" in path.parts or path.suffix not in (".json", ".jsonl"):
            continue
        texts = path.read_text().splitlines() if path.suffix == ".jsonl" else [path.read_text()]
        for n, text in enumerate(texts, 1):
            try:
                json.loads(text)
            except ValueError:
                bad.append(f"{path.relative_to(root)}:{n} is not whole JSON")
    return bad


def series_problems(series: Path, planned: int) -> tuple[list[str], int, int]:
    """One series directory: its episode lines numbered 0..n-1 once each, a directory per line and none
    without one, each directory's episode.json its line's episode, and its plan complete (each planned
    episode used or given up after its tries, rundir/schedule.py) with no episode played past it.
    Returns the problems, the episodes used and those given up."""
    from pillagerbench.rundir import RunDir, progress

    name = series.relative_to(series.parents[2])
    run = RunDir(series)
    lines = [_parsed(x) or {} for x in _lines(run.episodes_path)]  # a torn line: whole_records names it
    indices = [r.get("episode") for r in lines]
    out = []
    if indices != list(range(len(indices))):
        out.append(f"{name}: episode lines {indices}, not 0..{len(indices) - 1} once each")
    dirs = {i for i, _ in run.episode_dirs()}
    if dirs != set(indices):
        out.append(f"{name}: episode directories {sorted(dirs)} but lines {sorted(set(indices), key=str)}")
    for i in (x for x in indices if isinstance(x, int)):
        record = run.record_path(i)
        if not record.exists() or (_parsed(record.read_text()) or {}).get("episode") != i:
            out.append(f"{name}: episode_{i:03d}/episode.json missing or not its line's")
    done = progress(run.finished(), planned)
    if not done.complete or len(lines) != done.used + done.spoiled:
        out.append(f"{name}: {done.used} used + {done.given_up} given up of {planned} planned, {len(lines)} played")
    return out, done.used, done.given_up


def check(root: Path, target: Target, kill: Kill) -> None:
    """Everything wrong with a finished run, into `kill.problems`: lost, doubled or half-written episodes,
    records that do not parse, a plan left unfinished, a bundle of the run that fails `verify`, and a
    report counting other than the plan."""
    expected = target.expected(root)
    kill.problems += whole_records(root)
    found = set(root.glob(target.series))
    if found != set(expected):
        kill.problems.append(f"series {sorted(p.name for p in found)}, planned {sorted(p.name for p in expected)}")
    used = 0
    for series, planned in expected.items():
        problems, n, given_up = series_problems(series, planned)
        kill.problems += problems
        used, kill.given_up = used + n, kill.given_up + given_up
    kill.problems += target.finished(root)
    with tempfile.TemporaryDirectory() as out_dir:
        kill.problems += bundle_problems(target.runs(root), used, Path(out_dir))
    if used + kill.given_up != target.planned:
        kill.problems.append(f"the run used {used} and gave up {kill.given_up}; an unkilled run plans {target.planned}")


def bundle_problems(runs: list[Path], used: int, out_dir: Path) -> list[str]:
    """The run exported as a results bundle (`pillagerbench export`, in-process): `pillagerbench verify`
    passes it (its bundle.json's count of used episodes among its checks), bundle.json counts the `used`
    episodes of the run directories, and the report read from the bundle counts them too."""
    from pillagerbench.cli.commands import main
    from pillagerbench.metrics.verified import bundle_problems as verify
    from pillagerbench.report.build import build_report
    from pillagerbench.rundir.bundle import unpack

    bundle = out_dir / "killed.tar.gz"
    if main(["export", *map(str, runs), "--out", str(bundle)]) != 0:
        return ["export of the run failed"]
    info = unpack(bundle)[1]
    # verify's checks (`pillagerbench verify` prints them); a working tree edited while the run was killed and
    # resumed stamps the resumed episodes with another suite hash than the manifest's: that one is let be
    moved = len(info["suites"]) > 1
    disagree = [p for p in verify(bundle)[0] if not (moved and SUITE_MOVED.search(p))]
    if disagree:
        return [f"verify fails the bundle of the run ({bundle.name}): {disagree[0]}"]
    in_info = info["episodes_used"]
    # mix_suites: a working tree edited while the run was killed and resumed stamps two suite hashes
    counted = build_report([bundle], out_dir / "report", with_replays=False, mix_suites=True)["episodes"]
    if in_info != used or counted != used:
        return [f"the bundle says {in_info} episode(s) used and its report counts {counted}; the run used {used}"]
    return []


# --- the kill ------------------------------------------------------------------------------------------


def children(proc: subprocess.Popen, kind: str) -> list[psutil.Process]:
    """The run's processes of one kind (a child's kind by its command line)."""
    found = []
    for child in psutil.Process(proc.pid).children(recursive=True):
        try:
            if MARKS[kind] in " ".join(child.cmdline()):
                found.append(child)
        except psutil.Error:
            continue  # gone meanwhile
    return found


def _wait_for_moment(proc: subprocess.Popen, root: Path, target: Target, kill: Kill, start: float) -> bool:
    """Until the drawn moment (False when the run ended first)."""
    while proc.poll() is None:
        if kill.at_s is not None and time.monotonic() - start >= kill.at_s:
            return True
        if kill.after_records is not None and records(root, target) >= kill.after_records:
            return True
        time.sleep(0.02)
    return False


def _victim(
    proc: subprocess.Popen, root: Path, target: Target, kill: Kill, rng: random.Random
) -> psutil.Process | None:
    """The process to kill: the runner, a child of the drawn kind (waiting up to 10 s for one to be
    there: a server starts a second or two after the runner) or the target's outside process of that
    kind; the runner when none comes."""
    outside = target.outside(root, kill.asked)
    if outside is not None:
        kill.killed = kill.asked
        return outside
    deadline = time.monotonic() + 10
    while kill.asked != "runner" and proc.poll() is None and time.monotonic() < deadline:
        found = children(proc, kill.asked)
        if found:
            kill.killed = kill.asked
            return rng.choice(found)
        time.sleep(0.05)
    if proc.poll() is not None:
        return None
    kill.killed = "runner"
    return psutil.Process(proc.pid)


def _kind(process: psutil.Process) -> str:
    try:
        line = " ".join(process.cmdline())
    except psutil.Error:
        return "gone"
    return next((kind for kind, mark in MARKS.items() if mark in line), f"other ({line[:80]})")


def _kill_runner(proc: subprocess.Popen, target: Target, kill: Kill) -> None:
    """SIGKILL the runner alone, as a crash would; note its children still alive ORPHAN_WAIT_S later (by
    kind), then kill them (the arena server runs in a session of its own: the runner's group is not its)."""
    left = psutil.Process(proc.pid).children(recursive=True)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    _, alive = psutil.wait_procs(left, timeout=ORPHAN_WAIT_S)
    kinds = [_kind(p) for p in alive]
    kill.orphans = sorted(k for k in kinds if not any(mark in k for mark in target.lingering))
    kill.lingering = sorted(k for k in kinds if any(mark in k for mark in target.lingering))
    for leftover in alive:
        try:
            leftover.kill()
        except psutil.NoSuchProcess:
            pass
    psutil.wait_procs(alive, timeout=10)


def strike(proc: subprocess.Popen, root: Path, target: Target, kill: Kill) -> None:
    """Wait for the drawn moment, then kill; after a child's kill wait for the run to end by itself."""
    start = time.monotonic()
    if not _wait_for_moment(proc, root, target, kill, start):
        kill.killed, kill.moment = "none", "the run ended first"
        return
    victim = _victim(proc, root, target, kill, random.Random(kill.seed + 1))
    if victim is None:
        kill.killed, kill.moment = "none", "the run ended first"
        return
    kill.records_at_kill = records(root, target)
    kill.moment = moment(root, target, alive=True)
    if kill.killed == "runner":
        _kill_runner(proc, target, kill)
        return
    try:
        victim.kill()
    except psutil.NoSuchProcess:
        pass
    if kill.killed not in MARKS:  # an outside process: its owner starts it again a moment later
        psutil.wait_procs([victim], timeout=10)
        time.sleep(DOWN_S)
        target.revive(root, kill.killed)
    try:
        proc.wait(timeout=3 * target.span_s + 60)
        kill.run_exit = proc.returncode
    except subprocess.TimeoutExpired:
        kill.hung = True
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()


def run_kill(root: Path, target: Target, kill: Kill) -> Kill:
    """Start, kill as drawn, resume when the run did not end well by itself, check."""
    began = time.monotonic()
    root.mkdir(parents=True, exist_ok=True)
    try:
        target.prepare(root)
        _play(root, target, kill)
        check(root, target, kill)
    finally:
        target.cleanup(root)
    kill.wall_s = round(time.monotonic() - began, 1)
    return kill


def _play(root: Path, target: Target, kill: Kill) -> None:
    """The run started, killed as drawn, and resumed when it did not end well by itself."""
    proc = start_cli(*target.start(root), cwd=ROOT)
    try:
        strike(proc, root, target, kill)
        if proc.poll() is None and kill.killed == "none":
            proc.wait(timeout=3 * target.span_s + 60)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    kill.output = proc.stdout.read() if proc.stdout else ""
    if kill.killed == "none":
        kill.run_exit = proc.returncode
    if kill.run_exit != 0:
        kill.resumed = True
        done = run_cli(ROOT, *target.resume(root), timeout=6 * target.span_s + 120)
        kill.resume_exit = done.returncode
        kill.output += "\n--- resume ---\n" + done.stdout + done.stderr
        if done.returncode != 0:
            kill.problems.append(f"the resume exited {done.returncode}: {(done.stderr or done.stdout)[-300:]}")
