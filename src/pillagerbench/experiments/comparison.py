"""What a `compare` is and what it found, read from its run directory: the Comparison (compare.json), A's
score in each pair so far, and the Answer (the verdict, the log-likelihood ratio after each pair, pairs,
episodes and dollars) that the command prints and the report opens with (report/build.py).

A comparison is finished when its test decided or its cap was reached (`settle`): each series' planned
episodes become the ones it played (experiment.json, series.json), so `report`, `verify`, `export`
and `run resume=` read its series as finished, and compare.json records the answer under `decided`.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from pillagerbench.config.sides import other_side
from pillagerbench.llm.ledger import read_ledger
from pillagerbench.rundir import EpisodeRecord, RunDir, spoiled
from pillagerbench.rundir.experiment import read_experiment, write_experiment_file
from pillagerbench.rundir.whole import replace_json
from pillagerbench.stats.result import result
from pillagerbench.stats.sprt import BETTER, NOT_BETTER, UNDECIDED, Bounds, llr, verdict

FILE = "compare.json"
SAID = {BETTER: "is better than", NOT_BETTER: "is not better than", UNDECIDED: "undecided against"}


@dataclass
class Comparison:
    """What a compare plays and how it decides (compare.json)."""

    a: str
    b: str
    opponent: str | None = None
    bounds: Bounds = field(default_factory=Bounds)
    cap: int = 0  # pairs at most
    game: list[str] = field(default_factory=list)  # the overrides both entrants play under

    def series(self) -> dict[str, tuple[str, str]]:
        """Series id -> (red, blue): each entrant on each side against the opponent, or each other."""
        if self.opponent is None:
            return {"a_red": (self.a, self.b), "b_red": (self.b, self.a)}
        o = self.opponent
        return {"a_red": (self.a, o), "b_red": (self.b, o), "a_blue": (o, self.a), "b_blue": (o, self.b)}

    def pair(self, k: int) -> tuple[str, str, int]:
        """The series holding A's and B's episode of pair k, and its place among their used episodes."""
        if self.opponent is None:
            return "a_red", "b_red", k
        side = "red" if k % 2 == 0 else "blue"
        return f"a_{side}", f"b_{side}", k // 2

    def write(self, run_dir: Path, decided: dict[str, Any] | None = None) -> None:
        """compare.json (replaced whole: a kill leaves the old one or the new one)."""
        replace_json(
            run_dir / FILE,
            {**asdict(self), "bounds": asdict(self.bounds), **({"decided": decided} if decided else {})},
            indent=1,
        )


def read(run_dir: Path) -> Comparison | None:
    """The comparison of a run directory; None when it is not a compare's."""
    path = Path(run_dir) / FILE
    if not path.exists():
        return None
    data = json.loads(path.read_text())
    data.pop("decided", None)
    return Comparison(**{**data, "bounds": Bounds(**data["bounds"])})


def used(series_dir: Path) -> list[EpisodeRecord]:
    """A series' results so far: its finished episodes that are not spoiled, in order."""
    finished = RunDir(series_dir).finished()
    return [finished[i] for i in sorted(finished) if not spoiled(finished[i])]


def _points(rec: EpisodeRecord, entrant_side: str) -> float:
    return float((rec.red_score if entrant_side == "red" else rec.blue_score) or 0.0)


def _result(rec: EpisodeRecord, side: str) -> float:
    return result(_points(rec, side), _points(rec, other_side(side)))


def pair_scores(c: Comparison, run_dir: Path) -> list[float]:
    """A's score in each complete pair so far, in order."""
    rundir, eps = RunDir(run_dir), {}
    for sid in c.series():
        eps[sid] = used(rundir.series_dir(sid))
    out = []
    for k in range(c.cap):
        sa, sb, i = c.pair(k)
        if i >= len(eps[sa]) or i >= len(eps[sb]):
            break
        if c.opponent is None:  # A red in a_red, A blue in b_red
            out.append((_result(eps[sa][i], "red") + _result(eps[sb][i], "blue")) / 2)
        else:
            side = sa.removeprefix("a_")
            a, b = _points(eps[sa][i], side), _points(eps[sb][i], side)
            out.append(result(a, b))  # A's points against B's
    return out


def dollars(run_dir: Path, c: Comparison) -> str:
    """What the LLM calls of every series cost ("$0.0000"; "unknown" when a call had no price)."""
    ledgers = [RunDir(RunDir(run_dir).series_dir(sid)).ledger_path for sid in c.series()]
    calls = [r for path in ledgers if path.exists() for r in read_ledger(path)]
    if any(r.get("cost_usd") is None for r in calls if "cost_usd" in r):
        return "unknown (a call had no price)"
    return f"${sum(float(r.get('cost_usd') or 0.0) for r in calls):.4f}"


@dataclass(frozen=True)
class Answer:
    """What a comparison found so far: its verdict, A's pair scores and the LLR after each pair."""

    comparison: Comparison
    verdict: str
    scores: tuple[float, ...]
    path: tuple[float, ...]  # the log-likelihood ratio after pair 1, 2, ...
    episodes: int  # finished episodes of every series (spoiled ones included: they were played)
    dollars: str

    @property
    def finished(self) -> bool:
        """The test decided, or the cap's pairs were all played."""
        return self.verdict != UNDECIDED or len(self.scores) >= self.comparison.cap

    def line(self) -> str:
        """The command's last line, and the report's first."""
        c, b = self.comparison, self.comparison.bounds
        cap = f" at the cap ({c.cap} pairs)" if self.verdict == UNDECIDED else ""
        if not self.finished:
            cap = f" so far ({len(self.scores)} of up to {c.cap} pairs; unfinished: compare resume=RUN_DIR)"
        rates = f"α={b.alpha:g}, β={b.beta:g}, p0={b.p0:g}, p1={b.p1:g}"
        spent = f"{len(self.scores)} pairs, {self.episodes} episodes, {self.dollars}"
        return f"compare: {c.a} {SAID[self.verdict]} {c.b}{cap} (SPRT {rates}; {spent})"


def answer(c: Comparison, run_dir: Path) -> Answer:
    scores = pair_scores(c, run_dir)
    path = tuple(llr(scores[: k + 1], c.bounds) for k in range(len(scores)))
    episodes = sum(len(RunDir(RunDir(run_dir).series_dir(s)).finished()) for s in c.series())
    return Answer(c, verdict(scores, c.bounds), tuple(scores), path, episodes, dollars(run_dir, c))


def settle(run_dir: Path, found: Answer) -> None:
    """A finished comparison's series planned what they played; compare.json says what it decided."""
    c = found.comparison
    played = {sid: len(used(RunDir(run_dir).series_dir(sid))) for sid in c.series()}
    data = read_experiment(run_dir)
    for s in data.series:
        s["episodes"] = played.get(s["id"], s["episodes"])
    write_experiment_file(run_dir, data)
    for sid, n in played.items():
        path = RunDir(RunDir(run_dir).series_dir(sid)).series_path
        if path.exists():
            replace_json(path, {**json.loads(path.read_text()), "episodes": n}, indent=1)
    c.write(run_dir, {"verdict": found.verdict, "pairs": len(found.scores), "episodes": found.episodes})
