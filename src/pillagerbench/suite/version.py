"""The suite version: a human name (`suite 1.0`) and a sha256 over every file that can move a score.

`SCORE_FILES` (data, globs under the package) says which files count: the scenarios (arenas, layouts,
game masters), the built-in opponents (their team modules and scripts), the bots' primitives and code,
the server's plugins and tables, scoring, the clock and upstream's step waits (the team-loop timings),
and the npm lock. The hash is sha256 over one line per file, `path\\0sha256(content)`, in path order
(caches and compiled files left out), so it moves exactly when one of those files does.

`suite/suite_versions.json` (beside this module) records each released version's hash; a test fails when the
files no longer hash to the newest recorded one (docs/suite-versions.md says what to do). The suite a
run is played under is that version's name when the hash is recorded, else the newest name + "+dev".
`pillagerbench suite` prints it; `pillagerbench suite --record` records today's hash.
"""

from __future__ import annotations

import hashlib
import json
import sys
from functools import lru_cache
from pathlib import Path

from pillagerbench.config.args import Parser
from pillagerbench.suite.conditions import defaults_from

PACKAGE = Path(__file__).resolve().parents[1]
VERSIONS = PACKAGE / "suite/suite_versions.json"
UNVERSIONED = "unversioned"  # what a run written before suite versions reads as

SCORE_FILES: tuple[str, ...] = (
    "scenarios/**/*",  # scenarios, arenas, layouts, game masters
    "teams/scripts/**/*",  # the built-in opponents' scripts
    "teams/mushroom_war.py",
    "teams/dash_and_dine.py",
    "teams/scripted.py",
    "js/bot/**/*",  # primitives (and their LLM documentation), the bot, the sandbox
    "js/server/**/*",  # plugins and tables
    "js/clock/**/*",  # the game clock of the server and the bots (clock=lockstep)
    "js/package-lock.json",  # the pinned server and bot packages
    "match/scoring.py",
    "match/game.py",  # the clock, the game master's period, the whistle
    "match/player.py",  # upstream's step waits around each run (the team-loop timings)
    "players/placement.py",  # how each player is put back at every reset (place, look, items)
    "server/clock.py",  # the lockstep clock's Python side: what holds the world, rests, who is idle
    "metrics/formulas.py",  # P, S, D, W and each scenario's reported scale (Dash & Dine x0.1)
)
_SKIP_PARTS = {"__pycache__", "node_modules"}
_SKIP_SUFFIXES = {".pyc", ".pyo"}


def score_files(root: Path = PACKAGE, patterns: tuple[str, ...] = SCORE_FILES) -> list[Path]:
    """Every file the globs match under `root`, sorted, without caches and compiled files."""
    found = {p for pattern in patterns for p in root.glob(pattern) if p.is_file()}
    return sorted(
        (p for p in found if not _SKIP_PARTS & set(p.relative_to(root).parts) and p.suffix not in _SKIP_SUFFIXES),
        key=lambda p: p.relative_to(root).as_posix(),
    )


def suite_hash(root: Path = PACKAGE, patterns: tuple[str, ...] = SCORE_FILES) -> str:
    """sha256 (hex) over the score files' paths and contents, then the defaults of the rules
    (suite/conditions.py: the tick rate, the episode's length ... as conf/ sets them for each scenario)."""
    outer = hashlib.sha256()
    for path in score_files(root, patterns):
        inner = hashlib.sha256(path.read_bytes()).hexdigest()
        outer.update(f"{path.relative_to(root).as_posix()}\0{inner}\n".encode())
    for scenario, values in defaults_from(root / "conf").items():
        outer.update(f"rules\0{scenario}\0{json.dumps(values, sort_keys=True)}\n".encode())
    return outer.hexdigest()


def recorded(path: Path = VERSIONS) -> dict[str, str]:
    """Released versions in order: name -> hash."""
    return {v["name"]: v["sha256"] for v in json.loads(path.read_text())["versions"]}


def same_version(path: Path = VERSIONS) -> dict[str, str]:
    """Every recorded hash -> the hash its version is recorded under now: a version re-recorded for a
    change that moved no score (a restructure) keeps its earlier hashes (`earlier`), so that its runs
    before and after are one version."""
    out: dict[str, str] = {}
    for v in json.loads(path.read_text())["versions"]:
        out |= dict.fromkeys([*v.get("earlier", []), v["sha256"]], v["sha256"])
    return out


def label(name: str, digest: str) -> str:
    """How a suite is written in records and tables: `suite 1.0@<first 16 hex>`."""
    return f"{name}@{digest[:16]}"


def name_of(digest: str, versions: dict[str, str], earlier: dict[str, str] | None = None) -> str:
    """The version a hash is (its recorded name, also under an earlier hash of that version), else the
    newest name + "+dev"."""
    by_hash = {h: n for n, h in versions.items()}
    return by_hash.get((earlier or {}).get(digest, digest)) or f"{list(versions)[-1]}+dev"


def one_version(label_hash: str, path: Path = VERSIONS) -> str:
    """A label's hash (16 hex or more) as the hash its version is recorded under now (16 hex); other
    hashes as given. Runs whose hashes give the same answer played the same suite."""
    for digest, now in same_version(path).items():
        if label_hash and digest.startswith(label_hash):
            return now[: len(label_hash)]
    return label_hash


@lru_cache(maxsize=1)
def current() -> dict[str, str]:
    """This installation's suite: {"name", "sha256", "label"} (computed once per process)."""
    digest = suite_hash()
    name = name_of(digest, recorded(), same_version())
    return {"name": name, "sha256": digest, "label": label(name, digest)}


def check(root: Path = PACKAGE, path: Path = VERSIONS) -> str | None:
    """None when the score files hash to the newest recorded version, else the one line saying that
    scores may move and what to do (tests/test_suite.py fails with it)."""
    name, expected = list(recorded(path).items())[-1]
    actual = suite_hash(root)
    if actual == expected:
        return None
    return (
        f"files that can move scores changed without a new suite version ({name} recorded {expected[:16]}, "
        f"now {actual[:16]}): scores may move. Bump the version (pillagerbench suite --record 'suite X.Y'; "
        "--record alone re-records the same version for a change that moves no score), re-measure the "
        "reference figures (suite/reference_figures.json) and add an entry to docs/suite-versions.md"
    )


def record(name: str | None, path: Path = VERSIONS, root: Path = PACKAGE) -> str:
    """Record today's hash under `name` (a new version), or under the newest name when None (the same
    version, re-recorded); returns the line to print."""
    data = json.loads(path.read_text())
    digest = suite_hash(root)
    if name is None or name == data["versions"][-1]["name"]:
        newest = data["versions"][-1]
        if newest["sha256"] != digest:  # the same version: its earlier hash stays one of it
            newest["earlier"] = [*newest.get("earlier", []), newest["sha256"]]
        newest["sha256"] = digest
        name = newest["name"]
    elif name in recorded(path):
        raise ValueError(f"{name!r} is an earlier version; name a new one or leave the name out")
    else:
        data["versions"].append({"name": name, "sha256": digest})
    path.write_text(json.dumps(data, indent=1) + "\n")
    current.cache_clear()
    return f"recorded {label(name, digest)} in {path.name}"


def main(argv: list[str]) -> int:
    p = Parser(prog="pillagerbench suite", description=__doc__.split("\n\n")[0])
    p.add_argument("--hash", action="store_true", help="print the hash only")
    p.add_argument("--files", action="store_true", help="list the files the hash covers")
    p.add_argument(
        "--record",
        nargs="?",
        const="",
        metavar="NAME",
        help="record today's hash: under a new version NAME, or (no NAME) re-record the newest version",
    )
    a = p.parse_args(argv)
    if a.record is not None:
        try:
            print(record(a.record or None))
        except ValueError as exc:
            print(f"pillagerbench suite: {exc}", file=sys.stderr)
            return 2
        return 0
    suite = current()
    if a.hash:
        print(suite["sha256"])
        return 0
    if a.files:
        print("\n".join(p.relative_to(PACKAGE).as_posix() for p in score_files()))
        return 0
    print(f"{suite['name']} sha256:{suite['sha256']} ({len(score_files())} files)")
    return 0
