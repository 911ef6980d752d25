"""What a league has played, read only from its round directories: the usable episodes (through
metrics.runs, the report's reader), their outcomes for the ratings, and the budget spent.

`Played` is what `league play` reads between rounds: a round is read once, when finished, and kept
without its timelines, so an hour of play does not read every round again before each new one (the
process kept the memory of its largest read: docs/performance.md)."""

from __future__ import annotations

from dataclasses import dataclass, fields, replace
from pathlib import Path

import pandas as pd

from pillagerbench.league.ratings import Outcome
from pillagerbench.league.rounds import handed_over, round_dirs
from pillagerbench.llm.ledger import read_ledger
from pillagerbench.metrics.rows import EpisodeRow
from pillagerbench.metrics.runs import Runs, joined
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
    df = runs.episodes
    if not len(df):
        return []
    return [
        Outcome(
            r.scenario,
            r.red_name,
            r.blue_name,
            float(r.red_score),
            float(r.blue_score),
            (r.run, r.series, int(r.episode)),
        )
        for r in df.itertuples()
    ]


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


class Played:
    """What `league play` has read of the league's rounds and handed-over bundles: each read once, when every
    round is finished (play's loop reads only then), its rows kept without their timelines (the ratings
    need none); the checks and names across them are made again on every read (metrics/runs.py `joined`)."""

    def __init__(self, league_dir: Path, mix_suites: bool = False, verify: bool = True) -> None:
        self.league_dir, self.mix_suites, self.verify = league_dir, mix_suites, verify
        self._runs: dict[Path, Runs] = {}
        self._spent: dict[Path, Spent] = {}

    def runs(self) -> Runs:
        """The league's usable episodes, as `load` reads them but without their timelines."""
        for d in [*round_dirs(self.league_dir), *handed_over(self.league_dir)]:
            if d not in self._runs:
                self._runs[d] = _light(load_runs([d], self.mix_suites, self.verify))
        return joined(list(self._runs.values()), self.mix_suites)

    def spent(self) -> Spent:
        out = Spent()
        for d in round_dirs(self.league_dir):
            if d not in self._spent:
                self._spent[d] = _spent_in(d)
            out.add(self._spent[d])
        return out


def _light(runs: Runs) -> Runs:
    """The runs without what the ratings do not read: timelines and the LLM calls."""
    return replace(runs, rows=_untimed(runs.rows), spoiled_rows=_untimed(runs.spoiled_rows), ledger=[])


def _untimed(rows: list[EpisodeRow]) -> list[EpisodeRow]:
    return [r.model_copy(update={"t": (), "red_t": (), "blue_t": ()}) for r in rows]
