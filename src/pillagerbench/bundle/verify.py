"""`pillagerbench verify FILE`: check a results bundle and name every disagreement, one line each:
every file against its sha256 (changed, missing, not listed); the suite versions bundle.json states
against the episodes' own records (and whether each is a released version, and this installation's);
each finished episode's scores against its recorded score timeline (the final score is the timeline's
last point; upstream's scoring against timeline_upstream.json), its headline score, its winner and
its episode.json; the harness failures bundle.json counts against the records. Exit 0 when all
agree, 1 when something disagrees, 2 when the file is not a readable bundle."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from pillagerbench.args import Parser
from pillagerbench.bundle.export import summary
from pillagerbench.metrics.runs import Runs, load_runs
from pillagerbench.rundir import RunDir, winner_of
from pillagerbench.rundir.bundle import checksum_problems, unpack
from pillagerbench.suite import UNVERSIONED, current, label, recorded

SIDES = ("red", "blue")


def _read(path: Path) -> Any:
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return None


def _final(path: Path) -> dict | None:
    timeline = _read(path)
    return timeline[-1] if isinstance(timeline, list) and timeline else None


def episode_problems(run: RunDir, rec: dict[str, Any]) -> list[str]:
    """What disagrees in one finished, ok episode: its scores against its timelines, its headline score,
    its winner, its episode.json."""
    i, out = int(rec["episode"]), []
    for scoring, scores in (rec.get("scores") or {"clean": {s: rec.get(f"{s}_score") for s in SIDES}}).items():
        last = _final(run.timeline_path(i, scoring))
        if last is None:
            out.append(f"{run.timeline_path(i, scoring).name}: missing or unreadable")
            continue
        for side in SIDES:
            if scores.get(side) != last.get(side):
                out.append(
                    f"{scoring} {side} score {scores.get(side)} in the record, the timeline ends at {last.get(side)}"
                )
    headline = (rec.get("scores") or {}).get(rec.get("scoring", "clean"))
    if headline and any(headline[s] != rec.get(f"{s}_score") for s in SIDES):
        out.append(
            f"red_score/blue_score {rec.get('red_score')}/{rec.get('blue_score')} are not its {rec.get('scoring')} scores"
        )
    if (
        "winner" in rec
        and rec.get("red_score") is not None
        and rec["winner"] != winner_of(rec["red_score"], rec["blue_score"])
    ):
        out.append(f"winner {rec.get('winner')!r} does not follow from {rec['red_score']}–{rec['blue_score']}")
    beside = _read(run.record_path(i))
    if beside is not None and beside != rec:
        keys = sorted(k for k in set(beside) | set(rec) if beside.get(k) != rec.get(k))
        out.append(f"{run.record_path(i).name} differs from its line in the episodes' list ({', '.join(keys)})")
    return [f"{run.episode(i)}: {p}" for p in out]


def score_problems(runs: Runs) -> list[str]:
    out = []
    for s in runs.series:
        run = RunDir(s.dir)
        for rec in run.read_lenient()[0].values():
            if rec.get("status", "ok") == "ok":
                out += episode_problems(run, rec)
    return out


def suite_lines(suites: list[str]) -> list[str]:
    """One line per suite version of the episodes: released or not, this installation's or not."""
    released = {label(n, h): n for n, h in recorded().items()}
    mine = current()["label"]
    what = {UNVERSIONED: "played before suite versions"} | dict.fromkeys(released, "a released version")
    return [
        f"{s}: {what.get(s, 'not a released version (files changed since one)')}"
        f"{'; this installation plays it' if s == mine else f'; this installation plays {mine}'}"
        for s in (name for entry in suites for name in entry.split(" = "))  # one version, two names
    ]


def verify(bundle: Path) -> tuple[list[str], list[str]]:
    """(disagreements, facts) of a bundle; the disagreements name the file or episode."""
    root, info = unpack(bundle)
    problems = checksum_problems(root)
    runs = load_runs([bundle], mix_suites=True)
    problems += [p.replace(str(root) + "/", "") for p in score_problems(runs)]
    again = summary(runs)
    for key in ("suites", "episodes_used", "faults"):
        if info.get(key) != again[key]:
            problems.append(f"bundle.json: {key} says {_short(info.get(key))}, the records say {_short(again[key])}")
    facts = suite_lines(runs.suites) + [
        f"{len(runs.runs)} run(s), {len(runs.episodes)} episode(s) used; harness failures in "
        f"{again['faults']['harness_episodes']} episode(s), the teams' own in {again['faults']['team_episodes']}"
    ]
    return problems, facts


def _short(value: Any) -> str:
    text = json.dumps(value, default=str)
    return text if len(text) <= 80 else text[:77] + "..."


def main(argv: list[str]) -> int:
    p = Parser(prog="pillagerbench verify", description=__doc__.split("\n\n")[0])
    p.add_argument("bundle", help="a results bundle (pillagerbench export)")
    a = p.parse_args(argv)
    problems, facts = verify(Path(a.bundle))
    for line in facts:
        print(line)
    for line in problems:
        print(f"disagrees: {line}")
    print(f"{a.bundle}: {'verified' if not problems else f'{len(problems)} disagreement(s)'}")
    return 1 if problems else 0
