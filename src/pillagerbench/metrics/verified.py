"""Results bundles checked when read: `load_runs`, every reader's way in (report, symmetry, fidelity,
calibrate, export, the league), verifies each bundle among its inputs first and refuses a failing one
in one line (ReportError, exit 2, nothing written); `verify=False` (--no-verify; league: no_verify=true)
reads it anyway and every table's title and notes say so (`Runs.unverified`, metrics/runs.py
`mixed_notes`). `bundle_problems` is the one verification; `pillagerbench verify` prints it.

A bundle's checks: every file against its sha256 (changed, missing, not listed); each manifest's suite
version against its episodes' records (a series' manifest against its episodes, an experiment's against
all of them); each finished episode's scores against its recorded score timeline (the final score is the
timeline's last point; upstream's scoring against timeline_upstream.json), its headline score, its winner
and its episode.json; bundle.json's suites, episode count and harness failures against the records.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from pillagerbench.config.sides import SIDES
from pillagerbench.metrics.faults import tally
from pillagerbench.metrics.runs import ReportError, Runs, read_runs
from pillagerbench.rundir import EpisodeRecord, RunDir, winner_of
from pillagerbench.rundir.bundle import checksum_problems, is_bundle, unpack
from pillagerbench.suite.version import UNVERSIONED, current, label, recorded, same_version


def summary(runs: Runs) -> dict:
    """What bundle.json says of the runs beyond their files (the checks recompute it)."""
    return {
        "suites": runs.suites,
        "episodes_used": len(runs.episodes),
        "faults": {**tally(runs.faults), "rows": [f.row() for f in runs.faults]},
    }


def _read(path: Path) -> Any:
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return None


def _final(path: Path) -> dict | None:
    timeline = _read(path)
    return timeline[-1] if isinstance(timeline, list) and timeline else None


def episode_problems(run: RunDir, rec: EpisodeRecord) -> list[str]:
    """What disagrees in one finished, ok episode: its scores against its timelines, its headline score,
    its winner, its episode.json."""
    i, out = rec.episode, []
    headline: dict[str, float | None] = {"red": rec.red_score, "blue": rec.blue_score}
    recorded: Mapping[str, Mapping[str, float | None]] = rec.scores or {"clean": headline}
    for scoring, scores in recorded.items():
        last = _final(run.timeline_path(i, scoring))
        if last is None:
            out.append(f"{run.timeline_path(i, scoring).name}: missing or unreadable")
            continue
        for side in SIDES:
            if scores.get(side) != last.get(side):
                out.append(
                    f"{scoring} {side} score {scores.get(side)} in the record, the timeline ends at {last.get(side)}"
                )
    own = rec.scores.get(rec.scoring)
    if own and any(own[s] != headline[s] for s in SIDES):
        out.append(f"red_score/blue_score {rec.red_score}/{rec.blue_score} are not its {rec.scoring} scores")
    if (
        rec.winner is not None  # a winner recorded
        and rec.red_score is not None
        and rec.blue_score is not None
        and rec.winner != winner_of(rec.red_score, rec.blue_score)
    ):
        out.append(f"winner {rec.winner!r} does not follow from {rec.red_score}–{rec.blue_score}")
    beside = run.files(i).record()
    if beside is None and run.record_path(i).exists():
        out.append(f"{run.record_path(i).name}: unreadable (half written?)")
    if beside is not None and beside != rec:
        mine, theirs = rec.to_dict(), beside.to_dict()
        keys = sorted(k for k in mine if mine[k] != theirs[k])
        out.append(f"{run.record_path(i).name} differs from its line in the episodes' list ({', '.join(keys)})")
    return [f"{run.episode(i)}: {p}" for p in out]


def _records(runs: Runs) -> dict[Path, list[EpisodeRecord]]:
    """Every series' finished records (ok or not) by series directory."""
    return {s.dir: list(RunDir(s.dir).read_lenient()[0].values()) for s in runs.series}


def score_problems(runs: Runs, records: dict[Path, list[EpisodeRecord]]) -> list[str]:
    return [p for s in runs.series for rec in records[s.dir] if rec.ok for p in episode_problems(RunDir(s.dir), rec)]


def manifest_problems(runs: Runs, records: dict[Path, list[EpisodeRecord]]) -> list[str]:
    """Each manifest whose suite version is not its episodes' (a series' manifest: its episodes; an
    experiment's: all of them), naming the versions and the episodes; versions compare by hash."""
    covers: dict[Path, list[tuple[str, EpisodeRecord]]] = {}
    for s in runs.series:
        for top in dict.fromkeys((s.dir, s.root)):  # a plain run is its own series
            covers.setdefault(top, []).extend((s.id, rec) for rec in records[s.dir])
    out = []
    for top, recs in covers.items():
        manifest = RunDir(top).manifest()
        if manifest is None:
            continue
        says = manifest.suite_label
        several = len({series for series, _ in recs}) > 1  # an experiment's manifest: name the series too
        # a resume under another suite says so in its series' resumes.jsonl: those episodes agree too
        resumed = [x for s in runs.series if s.dir == top or s.root == top for x in RunDir(s.dir).resumed_suites()]
        played = {label.rpartition("@")[2] for label in [says, *resumed]}
        other: dict[str, list[str]] = {}
        for series, rec in recs:
            if rec.suite.rpartition("@")[2] not in played:
                other.setdefault(rec.suite, []).append(f"{series}/{rec.episode}" if several else f"{rec.episode}")
        out += [
            f"{RunDir(top).manifest_path}: says {says}, but {len(eps)} episode(s) say {suite} ({_few(eps)})"
            for suite, eps in other.items()
        ]
    return out


def _few(items: list[str]) -> str:
    return ", ".join(items[:5]) + (f" and {len(items) - 5} more" if len(items) > 5 else "")


def suite_lines(suites: list[str]) -> list[str]:
    """One line per suite version of the episodes: released or not, this installation's or not."""
    names = {h: n for n, h in recorded().items()}
    released = {label(names[now], h): names[now] for h, now in same_version().items()}  # earlier hashes too
    mine = current()["label"]
    what = {UNVERSIONED: "played before suite versions"} | dict.fromkeys(released, "a released version")
    return [
        f"{s}: {what.get(s, 'not a released version (files changed since one)')}"
        f"{'; this installation plays it' if s == mine else f'; this installation plays {mine}'}"
        for s in (name for entry in suites for name in entry.split(" = "))  # one version, two names
    ]


def _short(value: Any) -> str:
    text = json.dumps(value, default=str)
    return text if len(text) <= 80 else text[:77] + "..."


_checked: dict[tuple[Path, int, int], tuple[list[str], list[str]]] = {}


def bundle_problems(bundle: Path) -> tuple[list[str], list[str]]:
    """(disagreements, facts) of a bundle; the disagreements name the file or episode (once per process
    and version of the file)."""
    root, info = unpack(bundle)
    stat = bundle.stat()
    key = (bundle.resolve(), stat.st_mtime_ns, stat.st_size)
    if key in _checked:
        return _checked[key]
    problems = checksum_problems(root)
    runs = read_runs([bundle], mix_suites=True)
    records = _records(runs)
    problems += [
        p.replace(str(root) + "/", "") for p in manifest_problems(runs, records) + score_problems(runs, records)
    ]
    again = summary(runs)
    for item in ("suites", "episodes_used", "faults"):
        if info.get(item) != again[item]:
            problems.append(f"bundle.json: {item} says {_short(info.get(item))}, the records say {_short(again[item])}")
    facts = suite_lines(runs.suites) + [
        f"{len(runs.runs)} run(s), {len(runs.episodes)} episode(s) used; harness failures in "
        f"{again['faults']['harness_episodes']} episode(s), the teams' own in {again['faults']['team_episodes']}"
    ]
    _checked[key] = (problems, facts)
    return problems, facts


def check_bundles(paths: list[Path]) -> None:
    """ReportError naming the first bundle among `paths` that fails its checks, and its first disagreement."""
    for bundle in (p for p in paths if is_bundle(p)):
        problems = bundle_problems(bundle)[0]
        if problems:
            raise ReportError(
                f"{bundle}: fails its checks ({len(problems)} disagreement(s), the first: {problems[0]}; "
                f"`pillagerbench verify {bundle}` names them all); refusing to read it. --no-verify "
                "(league: no_verify=true) reads it anyway, every table marked"
            )


def load_runs(paths: list[str | Path], mix_suites: bool = False, verify: bool = True) -> Runs:
    """The runs (metrics/runs.py `read_runs`), each results bundle among them verified first; with
    `verify=False` read anyway and marked unverified."""
    inputs = [Path(p) for p in paths]
    if verify:
        check_bundles(inputs)
    runs = read_runs(paths, mix_suites)
    if not verify:
        runs.unverified = list(runs.bundles)
    return runs
