"""The faults of the episodes read, counted and tabled: ours (the harness) apart from the teams' own.
Whose fault a record shows is decided in rundir/faults.py (the rules as data; a series uses them to
play a spoiled episode again); an episode with a fault of ours is spoiled and kept out of every score
(metrics/runs.py), so that no team's result carries our faults.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any

import pandas as pd

from pillagerbench.metrics.rows import EpisodeRow
from pillagerbench.rundir.faults import HARNESS, TEAM, Fault, faults

__all__ = ["HARNESS", "TEAM", "COLUMNS", "FaultRow", "fault_note", "faults", "faults_table", "name_entrants", "tally"]


@dataclass
class FaultRow:
    """One fault where it happened: the run, the series, the episode, and its side's entrant (as the
    episode's row names it; name_entrants). bundle.json keeps these rows as they are (`row`)."""

    run: str
    series: str
    episode: int
    whose: str
    kind: str
    side: str
    what: str
    entrant: str = ""

    @classmethod
    def at(cls, run: str, series: str, episode: int, fault: Fault) -> FaultRow:
        return cls(run, series, episode, fault.whose, fault.kind, fault.side, fault.what)

    @property
    def where(self) -> tuple[str, str, int]:
        return self.run, self.series, self.episode

    def row(self) -> dict[str, Any]:
        return asdict(self)


def tally(rows: list[FaultRow]) -> dict[str, Any]:
    """Episodes with a harness failure and with a team's own failure, and harness failures by kind."""
    harness = {r.where for r in rows if r.whose == HARNESS}
    team = {r.where for r in rows if r.whose == TEAM}
    kinds: dict[str, int] = {}
    for r in rows:
        if r.whose == HARNESS:
            kinds[r.kind] = kinds.get(r.kind, 0) + 1
    return {"harness_episodes": len(harness), "team_episodes": len(team), "harness_by_kind": kinds}


COLUMNS = ["whose", "kind", "run", "series", "episode", "side", "entrant", "what"]


def faults_table(rows: list[FaultRow]) -> pd.DataFrame:
    """The report's table: ours first, then the teams' own, each in run order."""
    frame = pd.DataFrame([r.row() for r in rows], columns=COLUMNS)
    return frame.sort_values("whose", key=lambda w: w != HARNESS, kind="stable").reset_index(drop=True)


def fault_note(rows: list[FaultRow]) -> list[str]:
    """One line counting both kinds apart ([] when no episode had either)."""
    if not rows:
        return []
    t = tally(rows)
    kinds = ", ".join(f"{kind} {n}" for kind, n in t["harness_by_kind"].items()) or "none"
    return [
        f"failures: ours (the harness) in {t['harness_episodes']} episode(s) ({kinds}), not used in any score (each played again while `retries` last); "
        f"the teams' own (their code, their team server, their budget) in {t['team_episodes']} episode(s)"
    ]


def name_entrants(found: list[FaultRow], rows: list[EpisodeRow]) -> None:
    """Every fault's `entrant`: its side's entrant as the episode's row names it (both, for a fault of
    the whole episode); '' for an episode that has no row (failed, half-written)."""
    sides = {(r.run, r.series, r.episode): (r.red, r.blue) for r in rows}
    for f in found:
        red, blue = sides.get(f.where, ("", ""))
        f.entrant = {"red": red, "blue": blue}.get(f.side, f"{red} vs {blue}" if red else "")
