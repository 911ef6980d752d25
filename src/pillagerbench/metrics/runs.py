"""Read run directories (experiments and plain `pillagerbench run` directories) into one table of
finished episodes, with what was skipped and why.

An episode is used when its line is in episodes.jsonl, its status is ok and its timeline.json
reaches the episode length. An episode scored as upstream (scoring=upstream) is read as upstream's
analysis read it: its score over time is upstream's samples (timeline_upstream.json, line i as
second i). Everything else is listed in `skipped` (failed episodes, half-written
episodes of a killed run, series that did not finish). Runs of different versions of a scenario
(or different episode lengths) are refused: their scores do not compare. So are episodes of different
suite versions (suite/version.py; records from before it read "unversioned") unless `mix_suites` asks for them,
and then `mixed_notes` says so. A results bundle (rundir/bundle.py) is read as the run directories in it,
named by the paths they were exported from; `read_runs` reads it as it is: readers call
metrics/verified.py `load_runs`, which verifies it first (or, asked not to, marks it in `unverified`,
and `mixed_notes` says so). Every finished episode's faults (metrics/faults.py: ours or the team's) are
in `faults`. Each side of an episode is its entrant (metrics/entrants.py): `red` and
`blue` are the entrants' names, which every table groups by.
An episode spoiled on our side (a fault of ours: provider unreachable,
server or bot crash, lag) is in no score: its row is in `spoiled`, not in `episodes`, and it is listed in
`skipped`; a series played another in its place (rundir/schedule.py). `index` (the learning curves' x)
counts a series' used episodes, so a spoiled one leaves no hole.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from pillagerbench.metrics.columns import SIDES
from pillagerbench.metrics.entrants import columns, series_entrants
from pillagerbench.metrics.faults import FaultRow, name_entrants
from pillagerbench.metrics.formulas import SCORE_SCALE
from pillagerbench.metrics.rows import EpisodeRow, frame, named
from pillagerbench.rundir import (
    EPISODES,
    EpisodeDir,
    EpisodeRecord,
    Manifest,
    RunDir,
    SeriesSpec,
    TimelinePoint,
    faults,
    progress,
    read_series,
    spoiled,
)
from pillagerbench.rundir.bundle import BundleError, bundle_runs, is_bundle
from pillagerbench.rundir.entrant import Entrant
from pillagerbench.suite.conditions import describe
from pillagerbench.suite.version import one_version

# the scorings an episode can record (match.SCORINGS): red_score/blue_score are the run's own scoring,
# and red_<mode>/blue_<mode> every scoring the episode recorded (else nan)


class ReportError(ValueError):
    """Runs that cannot be reported together; the message says why."""


@dataclass
class SeriesInfo(SeriesSpec):
    """A series as a reader of its run sees it: its spec, where it is, and what its manifest says."""

    run: Path = field(default_factory=Path)  # the run directory given to the reader (its name in a bundle)
    root: Path = field(default_factory=Path)  # that run directory on disk
    dir: Path = field(default_factory=Path)  # the series' own directory
    version: str = "?"  # the scenario's version (its manifest)
    episode_length: float = 120.0
    manifest: Manifest | None = None  # the series' manifest.json (None when not started)
    # side -> its entrant from the config (metrics/entrants.py)
    entrants: dict[str, Entrant] = field(default_factory=dict)


@dataclass
class Runs:
    rows: list[EpisodeRow]  # one per usable episode, typed (metrics/rows.py)
    series: list[SeriesInfo]
    ledger: list[dict]  # red-team LLM calls, each with "label" (its red entrant's row), "scenario", "run", "series"
    skipped: list[tuple[str, str]] = field(default_factory=list)  # (where, why)
    calibration_files: list[Path] = field(default_factory=list)
    runs: list[Path] = field(default_factory=list)  # every run's name (a bundle's: the paths exported)
    roots: dict[Path, Path] = field(default_factory=dict)  # a run's name -> its directory on disk
    faults: list[FaultRow] = field(default_factory=list)  # every finished episode's faults (metrics/faults.py)
    suites: list[str] = field(default_factory=list)  # the suite versions of the episodes used
    bundles: list[Path] = field(default_factory=list)  # results bundles among the inputs
    unverified: list[Path] = field(default_factory=list)  # bundles read without their checks (--no-verify)
    spoiled_rows: list[EpisodeRow] = field(default_factory=list)  # episodes spoiled on our side (in no score)
    episodes: pd.DataFrame = field(init=False)  # the table of `rows` (metrics/rows.py `frame`)
    spoiled: pd.DataFrame = field(init=False)  # the table of `spoiled_rows`, the same columns

    def __post_init__(self) -> None:
        self.episodes, self.spoiled = frame(self.rows), frame(self.spoiled_rows)


def mixed_notes(runs: Runs) -> list[str]:
    """What every table says of the runs it is made of: mixed suite versions or conditions, bundles read without
    their checks; none when neither."""
    out = []
    if len(runs.suites) >= 2:
        out.append(f"mixed suite versions or conditions: {', '.join(runs.suites)} (scores may not compare)")
    if runs.unverified:
        names = ", ".join(str(b) for b in runs.unverified)
        out.append(f"bundle not verified: {names} (--no-verify; its numbers may have been edited)")
    return out


def mixed_title(runs: Runs) -> str:
    """The mark a table's title gets when suite versions are mixed or a bundle was not verified ('' when not)."""
    return "".join(f" [{n}]" for n in mixed_notes(runs))


def reader_switches(parser: Any) -> None:
    """The switches of a command that reads runs (argparse): --mix-suites allows episodes of different
    suite versions, --no-verify reads a results bundle that fails its checks; every table says so."""
    parser.add_argument(
        "--mix-suites", action="store_true", help="allow episodes of different suite versions (every table says so)"
    )
    parser.add_argument(
        "--no-verify",
        action="store_true",
        help="read results bundles without their checks (pillagerbench verify); every table says so",
    )


def beside(first: Path, name: str) -> Path:
    """Where a command writes by default: FIRST_RUN/name, or for a bundle BUNDLE_name beside it."""
    return first.with_name(f"{first.name.split('.')[0]}_{name}") if first.is_file() else first / name


def _inputs(paths: list[Path]) -> list[tuple[Path, Path]]:
    """(directory to read, the run's name) of every input: a run directory is itself; a bundle gives
    its runs, named by the paths they were exported from."""
    out = []
    for path in paths:
        if is_bundle(path):
            try:
                out += [(disk, Path(source)) for disk, source in bundle_runs(path)]
            except BundleError as exc:
                raise ReportError(str(exc)) from None
        else:
            out.append((path, path))
    return out


def _series_of(run: Path, name: Path) -> list[SeriesInfo]:
    found = read_series(run)
    if found is None:
        if not run.exists():
            raise ReportError(f"{run}: not a run directory or bundle (no such path)")
        raise ReportError(f"{run}: not a run directory (no experiment.json or manifest.json)")
    out = []
    for spec, series_dir in found[1]:
        manifest = RunDir(series_dir).manifest()
        out.append(
            SeriesInfo(
                **{f.name: getattr(spec, f.name) for f in fields(SeriesSpec)},
                run=name,
                root=run,
                dir=series_dir,
                version=manifest.scenario_version if manifest else "?",
                episode_length=spec.config.episode_length,
                manifest=manifest,
                entrants=series_entrants(spec.config),
            )
        )
    return out


def _load_series(
    s: SeriesInfo, rows: list[EpisodeRow], skipped: list, found: list[FaultRow], spoilt: list[EpisodeRow]
) -> None:
    finished = _finished_episodes(s, skipped)
    scale = SCORE_SCALE.get(s.scenario, 1.0)
    used = 0
    for i in sorted(finished):
        rec = finished[i]
        found += [FaultRow.at(str(s.run), s.id, i, f) for f in faults(rec)]
        ep = RunDir(s.dir).files(i)
        timeline = _timeline(s, rec, ep, skipped)
        if timeline is None:
            continue
        row = _row(s, i, rec, ep.path, timeline, scale, used + s.episode_offset)
        kind = spoiled(rec)
        if kind:
            skipped.append((str(ep.path), f"spoiled on our side ({kind}): in no score (the Failures table lists it)"))
            spoilt.append(row)
        else:
            rows.append(row)
            used += 1


def _finished_episodes(s: SeriesInfo, skipped: list) -> dict[int, EpisodeRecord]:
    """The series' finished episodes by index; what is not started, half-written or missing goes to `skipped`."""
    where = str(s.dir)
    if not s.dir.exists():
        skipped.append((where, f"series not started ({s.episodes} episode(s) missing)"))
        return {}
    rundir = RunDir(s.dir)
    finished, bad = rundir.read_lenient()
    for n in bad:
        skipped.append((f"{where}/{EPISODES}:{n}", "a line cut short (the run was killed while writing it)"))
    for i, d in rundir.episode_dirs():
        if i not in finished:
            skipped.append(
                (str(d), f"half-written: no line in {EPISODES} (killed mid-episode; resume=RUN_DIR plays it again)")
            )
    done = progress(finished, s.episodes, s.config.retries)
    if done.given_up:
        skipped.append(
            (
                where,
                f"{done.given_up} of {s.episodes} planned episode(s) given up: every try spoiled on our side "
                f"(retries={s.config.retries}); {done.used} of {s.episodes} used",
            )
        )
    if not done.complete:
        skipped.append((where, f"{done.used} of {s.episodes} episode(s) used so far (unfinished run? resume=RUN_DIR)"))
    return finished


def _timeline(s: SeriesInfo, rec: EpisodeRecord, ep: EpisodeDir, skipped: list) -> list[TimelinePoint] | None:
    """An ok episode's score timeline (upstream's rewards file for its scoring), or None with the reason in
    `skipped` (failed, half-written or cut short before the whistle)."""
    where, name = str(ep.path), ep.timeline_path().name
    if not rec.ok:
        skipped.append((where, f"failed: {rec.error}"))
        return None
    try:
        timeline = ep.timeline()
    except FileNotFoundError:
        skipped.append((where, f"half-written: no {name}"))
        return None
    except ValueError:
        skipped.append((where, f"half-written: {name} cut short"))
        return None
    if not timeline or float(timeline[-1]["t"]) < s.episode_length:
        end = timeline[-1]["t"] if timeline else None
        skipped.append((where, f"half-written: timeline ends at t={end}, before {s.episode_length:g} s"))
        return None
    if rec.scoring == "upstream" and ep.timeline_path("upstream").exists():
        # as upstream's analysis read it: line i of its rewards file stands for second i
        timeline = [{**p, "t": p["line"]} for p in ep.timeline("upstream")]
    return timeline


def _row(s: SeriesInfo, i: int, rec: EpisodeRecord, ep: Path, timeline: list, scale: float, index: int) -> EpisodeRow:
    """One episode's row of the table (`index`: its place among the series' used episodes, for curves)."""
    red_it = rec.iterations.get("red") or []
    names = {"red": s.red, "blue": s.blue}  # the entrants' names once every row is read (rows.named)
    return EpisodeRow(
        run=str(s.run),
        dir=str(ep),
        series=s.id,
        scenario=s.scenario,
        version=s.version,
        episode_length=s.episode_length,
        red=s.red,
        blue=s.blue,
        **columns({"red": rec.red_entrant, "blue": rec.blue_entrant}, s.entrants, names),
        red_team=s.red_team,
        blue_team=s.blue_team,
        design=s.design,
        variant=s.variant,
        repetition=s.repetition,
        group=s.group,
        group_x=s.group_x,
        episode=i,
        index=index,
        red_raw=float(rec.red_score or 0.0),
        blue_raw=float(rec.blue_score or 0.0),
        scale=scale,
        red_score=float(rec.red_score or 0.0) * scale,
        blue_score=float(rec.blue_score or 0.0) * scale,
        scoring=rec.scoring,
        suite=rec.suite,
        stamp=rec.stamp,  # the suite and the rules differing from its defaults (suite/conditions.py)
        rules=describe(rec.conditions),
        conditions=dict(rec.conditions),
        layout=rec.layout,
        seed=rec.seed,  # "paper", a seed or a layout file; split: paper | dev | test | custom
        split=rec.split,
        by_scoring={m: {side: float(points[side]) * scale for side in SIDES} for m, points in rec.scores.items()},
        team_protocol=rec.protocol,
        iterations=float(np.mean(red_it)) if red_it else np.nan,
        problems={k: list(v) for k, v in rec.problems.items()},
        server_tps=rec.server_tps,
        lagged=bool(rec.lagged),
        lag_reason=rec.lag_reason,
        t=tuple(float(p["t"]) for p in timeline),
        red_t=tuple(float(p["red"]) * scale for p in timeline),
        blue_t=tuple(float(p["blue"]) * scale for p in timeline),
    )


# what the readers compare across runs of a scenario: (scenario, version, episode length, run) of a series played
Comparable = tuple[str, str, float, str]


def comparable(series: list[SeriesInfo]) -> list[Comparable]:
    """What `check_comparable` reads of the series (those played: their directory exists)."""
    return [(s.scenario, s.version, s.episode_length, str(s.run)) for s in series if s.dir.exists()]


def check_comparable(found: list[Comparable]) -> None:
    """ReportError when the series of a scenario were played under different versions or episode lengths."""
    for at, what in ((1, "versions"), (2, "episode lengths")):
        seen: dict[str, dict] = {}
        for key in found:
            seen.setdefault(key[0], {}).setdefault(key[at], key[3])
        for scenario, values in seen.items():
            if len(values) > 1:
                detail = "; ".join(f"{v} in {run}" for v, run in values.items())
                raise ReportError(
                    f"refusing to mix {what} of {scenario}: {detail}. Their scores do not compare; "
                    "report them separately"
                )


def suites(stamps: list[tuple[str, str]], mix_suites: bool) -> list[str]:
    """The stamps of the episodes ((stamp, run) each: suite version and the rules differing from its defaults,
    suite/conditions.py), in order; more than one is refused unless `mix_suites`. A version is its hash: the
    same files named before and after their hash was recorded (`suite 1.0+dev@H`, `suite 1.0@H`) are
    one version, written with both names; so are a version's earlier hashes (re-recorded after a change
    that moved no score: suite.same_version)."""
    names: dict[str, list[str]] = {}
    where: dict[str, list[str]] = {}
    for stamp, run in stamps:
        digest, _, conditions = stamp.rpartition("@")[2].partition(" ")
        key = f"{one_version(digest)} {conditions}"  # the version (its hash, earlier ones too) and the conditions
        for seen, item in ((names, stamp), (where, run)):
            if item not in seen.setdefault(key, []):
                seen[key].append(item)
    labels = {key: " = ".join(found) for key, found in names.items()}
    if len(where) > 1 and not mix_suites:
        detail = "; ".join(f"{labels[key]} in {', '.join(runs)}" for key, runs in where.items())
        raise ReportError(
            f"refusing to mix suite versions or conditions: {detail}. Their scores may not compare; report them "
            "separately, or ask to mix them (--mix-suites; league: mix_suites=true)"
        )
    return list(labels.values())


def _named(where: str, roots: dict[Path, Path]) -> str:
    for name, root in roots.items():
        if name != root and where.startswith(str(root)):
            return str(name) + where[len(str(root)) :]
    return where


def read_runs(paths: list[str | Path], mix_suites: bool = False) -> Runs:
    """The runs as they are, bundles unchecked: readers use metrics/verified.py `load_runs`."""
    series: list[SeriesInfo] = []
    skipped: list[tuple[str, str]] = []
    rows: list[EpisodeRow] = []
    ledger: list[dict[str, Any]] = []
    cals: list[Path] = []
    found: list[FaultRow] = []
    spoilt: list[EpisodeRow] = []
    inputs = [Path(p) for p in paths]
    roots = {name: run for run, name in _inputs(inputs)}
    for name, run in roots.items():
        series += _series_of(run, name)
        if RunDir(run).calibration_path.exists():
            cals.append(RunDir(run).calibration_path)
    check_comparable(comparable(series))
    for s in series:
        _load_series(s, rows, skipped, found, spoilt)
        path = RunDir(s.dir).ledger_path
        if path.exists():
            from pillagerbench.llm.ledger import read_ledger

            ledger += [
                {**r, "label": s.red, "scenario": s.scenario, "series": s.id, "run": str(s.run)}
                for r in read_ledger(path)
                if r.get("team") == "red"
            ]
    every = named(rows + spoilt)  # red and blue: the entrants, in every table (spoiled episodes' too)
    rows, spoilt = every[: len(rows)], every[len(rows) :]
    name_entrants(found, every)  # the Failures table names them too
    _label_calls(ledger, rows)
    stamps = suites([(r.stamp, r.run) for r in rows], mix_suites)
    skipped = [(_named(where, roots), why) for where, why in skipped]  # a bundle's runs by their names
    return Runs(
        rows=rows,
        series=series,
        ledger=ledger,
        skipped=skipped,
        calibration_files=cals,
        runs=list(roots),
        roots=roots,
        faults=found,
        suites=stamps,
        bundles=[r for r in inputs if is_bundle(r)],
        spoiled_rows=spoilt,
    )


def _label_calls(ledger: list[dict[str, Any]], rows: list[EpisodeRow]) -> None:
    """Every red-team LLM call labelled as its series' red rows are (calls carry `run` and `series`)."""
    red = {(r.run, r.series): r.red for r in rows}
    for call in ledger:
        call["label"] = red.get((call["run"], call["series"]), call["label"])
