"""Read run directories (experiments and plain `pillagerbench run` directories) into one table of
finished episodes, with what was skipped and why.

An episode is used when its line is in episodes.jsonl, its status is ok and its timeline.json
reaches the episode length. An episode scored as upstream (scoring=upstream) is read as upstream's
analysis read it: its score over time is upstream's samples (timeline_upstream.json, line i as
second i). Everything else is listed in `skipped` (failed episodes, half-written
episodes of a killed run, series that did not finish). Runs of different versions of a scenario
(or different episode lengths) are refused: their scores do not compare.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from pillagerbench.match import SCORINGS
from pillagerbench.metrics.formulas import SCORE_SCALE
from pillagerbench.rundir import EPISODES, EpisodeRecord, RunDir, SeriesSpec, read_series

# the scorings an episode can record (match.SCORINGS): red_score/blue_score are the run's own scoring,
# and red_<mode>/blue_<mode> every scoring the episode recorded (else nan)


class ReportError(ValueError):
    """Runs that cannot be reported together; the message says why."""


@dataclass
class SeriesInfo(SeriesSpec):
    """A series as a reader of its run sees it: its spec, where it is, and what its manifest says."""

    run: Path = field(default_factory=Path)  # the run directory given to the reader
    dir: Path = field(default_factory=Path)  # the series' own directory
    version: str = "?"  # the scenario's version (its manifest)
    episode_length: float = 120.0
    manifest: dict = field(default_factory=dict)  # the series' manifest.json ({} when not started)


@dataclass
class Runs:
    episodes: pd.DataFrame  # one row per usable episode
    series: list[SeriesInfo]
    ledger: list[dict]  # red-team LLM calls, each with "label" (row) and "scenario"
    skipped: list[tuple[str, str]] = field(default_factory=list)  # (where, why)
    calibration_files: list[Path] = field(default_factory=list)
    runs: list[Path] = field(default_factory=list)


def _series_of(run: Path) -> list[SeriesInfo]:
    found = read_series(run)
    if found is None:
        raise ReportError(f"{run}: not a run directory (no experiment.json or manifest.json)")
    out = []
    for spec, series_dir in found[1]:
        manifest = RunDir(series_dir).manifest()
        out.append(
            SeriesInfo(
                **{f.name: getattr(spec, f.name) for f in fields(SeriesSpec)},
                run=run,
                dir=series_dir,
                version=str(manifest.get("scenario", {}).get("version", "?")),
                episode_length=float(spec.config.get("episode_length", 120)),
                manifest=manifest,
            )
        )
    return out


def _load_series(s: SeriesInfo, rows: list, skipped: list) -> None:
    finished = _finished_episodes(s, skipped)
    scale = SCORE_SCALE.get(s.scenario, 1.0)
    for i in sorted(finished):
        rec = finished[i]
        ep = RunDir(s.dir).episode(i)
        timeline = _timeline(s, rec, ep, skipped)
        if timeline is not None:
            rows.append(_row(s, i, rec, ep, timeline, scale))


def _finished_episodes(s: SeriesInfo, skipped: list) -> dict[int, dict]:
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
    missing = s.episodes - len(finished)
    if missing > 0:
        skipped.append((where, f"{missing} of {s.episodes} episode(s) not played (unfinished run? resume=RUN_DIR)"))
    return finished


def _timeline(s: SeriesInfo, rec: dict, ep: Path, skipped: list) -> list | None:
    """An ok episode's score timeline (upstream's rewards file for its scoring), or None with the reason in
    `skipped` (failed, half-written or cut short before the whistle)."""
    if rec.get("status") != "ok":
        skipped.append((str(ep), f"failed: {rec.get('error')}"))
        return None
    try:
        timeline = json.loads((ep / "timeline.json").read_text())
    except FileNotFoundError:
        skipped.append((str(ep), "half-written: no timeline.json"))
        return None
    except ValueError:
        skipped.append((str(ep), "half-written: timeline.json cut short"))
        return None
    if not timeline or float(timeline[-1]["t"]) < s.episode_length:
        end = timeline[-1]["t"] if timeline else None
        skipped.append((str(ep), f"half-written: timeline ends at t={end}, before {s.episode_length:g} s"))
        return None
    if rec.get("scoring") == "upstream" and (ep / "timeline_upstream.json").exists():
        # as upstream's analysis read it: line i of its rewards file stands for second i
        lines = json.loads((ep / "timeline_upstream.json").read_text())
        timeline = [{**p, "t": p["line"]} for p in lines]
    return timeline


def _row(s: SeriesInfo, i: int, data: dict, ep: Path, timeline: list, scale: float) -> dict:
    """One episode's row of the table."""
    rec = EpisodeRecord.from_dict(data)  # whichever version wrote it
    red_it = rec.iterations.get("red") or []
    by_mode = rec.scores
    alternatives = {
        f"{side}_{mode}": float(by_mode[mode][side]) * scale if mode in by_mode else np.nan
        for mode in SCORINGS
        for side in ("red", "blue")
    }
    return {
        "run": str(s.run),
        "dir": str(ep),
        "series": s.id,
        "scenario": s.scenario,
        "version": s.version,
        "episode_length": s.episode_length,
        "red": s.red,
        "blue": s.blue,
        "red_team": s.red_team,
        "blue_team": s.blue_team,
        "design": s.design,
        "variant": s.variant,
        "repetition": s.repetition,
        "group": s.group,
        "group_x": s.group_x,
        "episode": i,
        "index": i + s.episode_offset,
        "red_raw": float(rec.red_score or 0.0),
        "blue_raw": float(rec.blue_score or 0.0),
        "scale": scale,
        "red_score": float(rec.red_score or 0.0) * scale,
        "blue_score": float(rec.blue_score or 0.0) * scale,
        "scoring": rec.scoring,
        **alternatives,
        "team_protocol": rec.protocol,
        "iterations": float(np.mean(red_it)) if red_it else np.nan,
        "problems": {k: list(v) for k, v in rec.problems.items()},
        "server_tps": rec.server_tps,
        "lagged": bool(rec.lagged),
        "lag_reason": rec.lag_reason,
        "t": np.array([p["t"] for p in timeline], dtype=float),
        "red_t": np.array([p["red"] for p in timeline], dtype=float) * scale,
        "blue_t": np.array([p["blue"] for p in timeline], dtype=float) * scale,
    }


def _check_comparable(series: list[SeriesInfo]) -> None:
    for attr, what in (("version", "versions"), ("episode_length", "episode lengths")):
        seen: dict[str, dict] = {}
        for s in series:
            if s.dir.exists():
                seen.setdefault(s.scenario, {}).setdefault(getattr(s, attr), s.run)
        for scenario, values in seen.items():
            if len(values) > 1:
                detail = "; ".join(f"{v} in {run}" for v, run in values.items())
                raise ReportError(
                    f"refusing to mix {what} of {scenario}: {detail}. Their scores do not compare; "
                    "report them separately"
                )


def load_runs(paths: list[str | Path]) -> Runs:
    series: list[Any] = []
    skipped: list[Any] = []
    rows: list[Any] = []
    ledger: list[Any] = []
    cals: list[Any] = []
    runs = [Path(p) for p in paths]
    for run in runs:
        series += _series_of(run)
        if (run / "calibration.json").exists():
            cals.append(run / "calibration.json")
    _check_comparable(series)
    for s in series:
        _load_series(s, rows, skipped)
        path = RunDir(s.dir).ledger_path
        if path.exists():
            from pillagerbench.llm.ledger import read_ledger

            ledger += [
                {**r, "label": s.red, "scenario": s.scenario, "series": s.id}
                for r in read_ledger(path)
                if r.get("team") == "red"
            ]
    df = pd.DataFrame(rows)
    return Runs(episodes=df, series=series, ledger=ledger, skipped=skipped, calibration_files=cals, runs=runs)
