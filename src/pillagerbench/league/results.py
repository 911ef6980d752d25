"""What a league has played, read only from its round directories: the usable episodes (through
metrics.runs, the report's reader), their outcomes for the ratings, and the budget spent.

`Played` is what `league play` reads between rounds: a round is read once, when finished, and only its
outcomes kept, so an hour of play does not read every round again before each new one (the process kept
the memory of its largest read) nor keep every round's read (docs/performance.md)."""

from __future__ import annotations

from dataclasses import dataclass, fields
from pathlib import Path

import pandas as pd

from pillagerbench.league.ratings import Outcome
from pillagerbench.league.rounds import handed_over, round_dirs
from pillagerbench.llm.ledger import read_ledger
from pillagerbench.metrics.rows import EpisodeRow
from pillagerbench.metrics.runs import Comparable, Runs, check_comparable, comparable, suites
from pillagerbench.metrics.verified import load_runs
from pillagerbench.rundir import LEDGER, RunDir


@dataclass
class Spent:
    episodes: int = 0  # finished episode lines, failed ones included
    hours: float = 0.0  # wall time of those episodes
    llm_tokens: int = 0
    llm_cost_usd: float = 0.0  # of the calls whose cost is known: a lower bound when llm_unpriced_calls > 0
    llm_unpriced_calls: int = 0  # calls whose cost is unknown (no price for the model; llm/prices.py)

    def add(self, other: Spent) -> None:
        for f in fields(self):
            setattr(self, f.name, getattr(self, f.name) + getattr(other, f.name))

    def over(self, budget: dict[str, float | None]) -> str | None:
        """The first budget item used up ("episodes 4/4"), or None."""
        for key in ("episodes", "hours", "llm_tokens", "llm_cost_usd"):
            limit, used = budget.get(key), getattr(self, key)
            if limit is not None and used >= limit:
                return f"{key} {used:g}/{limit:g}"
        return None


def load(league_dir: Path, mix_suites: bool = False, verify: bool = True) -> Runs:
    """The league's rounds, the handed-over bundles verified first unless `verify` is False (no_verify=true)."""
    return load_runs([*round_dirs(league_dir), *handed_over(league_dir)], mix_suites, verify)


def outcomes(runs: Runs) -> list[Outcome]:
    return [_outcome(r) for r in runs.rows]


def _outcome(r: EpisodeRow) -> Outcome:
    """An episode's outcome for the ratings: the sides by the names the league gave them (`red_name`)."""
    return Outcome(r.scenario, r.red_name, r.blue_name, r.red_score, r.blue_score, (r.run, r.series, r.episode))


def ledger(runs: Runs) -> pd.DataFrame:
    """LLM calls of both sides, one row each: entrant, scenario, tokens, cost."""
    rows = []
    for s in runs.series:
        if not (s.dir / LEDGER).exists():
            continue
        for r in read_ledger(s.dir / LEDGER):
            entrant = {"red": s.red, "blue": s.blue}.get(str(r.get("team")))
            tokens = int(r.get("input_tokens") or 0) + int(r.get("output_tokens") or 0)
            rows.append({"entrant": entrant, "scenario": s.scenario, "tokens": tokens, "cost": r.get("cost_usd")})
    return pd.DataFrame(rows, columns=["entrant", "scenario", "tokens", "cost"])


def spent(league_dir: Path) -> Spent:
    out = Spent()
    for d in round_dirs(league_dir):
        out.add(_spent_in(d))
    return out


def _spent_in(round_dir: Path) -> Spent:
    out = Spent()
    for series in RunDir(round_dir).all_series():
        finished = RunDir(series).finished().values()
        out.episodes += len(finished)
        out.hours += sum(r.duration_s for r in finished) / 3600
        if (series / LEDGER).exists():
            for r in read_ledger(series / LEDGER):
                out.llm_tokens += int(r.get("input_tokens") or 0) + int(r.get("output_tokens") or 0)
                if "cost_usd" in r and r["cost_usd"] is None:
                    out.llm_unpriced_calls += 1
                else:
                    out.llm_cost_usd += float(r.get("cost_usd") or 0.0)
    return out


@dataclass(frozen=True)
class _Round:
    """What `Played` keeps of a round: each used episode's outcome with its layouts' split, and what the checks
    across rounds read (metrics/runs.py: the series' versions and episode lengths, the episodes' suites)."""

    outcomes: list[tuple[str, Outcome]]
    series: list[Comparable]
    stamps: list[tuple[str, str]]  # (stamp, run), each once

    @classmethod
    def of(cls, runs: Runs) -> _Round:
        return cls(
            [(r.split, _outcome(r)) for r in runs.rows],
            comparable(runs.series),
            list(dict.fromkeys((r.stamp, r.run) for r in runs.rows)),
        )


class Played:
    """What `league play` has read of the league's rounds and handed-over bundles: each read once, when every
    round is finished (play's loop reads only then), and of it kept only the outcomes and what the checks
    across rounds read (a round's whole read is ~30 KB an episode; an outcome ~0.3 KB)."""

    def __init__(self, league_dir: Path, mix_suites: bool = False, verify: bool = True) -> None:
        self.league_dir, self.mix_suites, self.verify = league_dir, mix_suites, verify
        self._rounds: dict[Path, _Round] = {}
        self._spent: dict[Path, Spent] = {}

    def outcomes(self, split: str) -> list[Outcome]:
        """The outcomes of the episodes of `split` (league/splits.py), as `outcomes(on_split(load(...)))` gives
        them; versions, episode lengths and suites refused mixed across rounds as within one."""
        for d in [*round_dirs(self.league_dir), *handed_over(self.league_dir)]:
            if d not in self._rounds:
                self._rounds[d] = _Round.of(load_runs([d], self.mix_suites, self.verify))
        rounds = list(self._rounds.values())
        check_comparable([key for r in rounds for key in r.series])
        suites([stamp for r in rounds for stamp in r.stamps], self.mix_suites)
        return [o for r in rounds for on, o in r.outcomes if on == split]

    def spent(self) -> Spent:
        out = Spent()
        for d in round_dirs(self.league_dir):
            if d not in self._spent:
                self._spent[d] = _spent_in(d)
            out.add(self._spent[d])
        return out
