"""The finished estimate of one entrant over some of its episodes: P, S, D and W, each a mean with its
95 % interval (formulas.Estimate). It is what metrics hands the report for each row of its tables,
computed here over the formulas (metrics/formulas.py, in the suite's hash); the report only formats it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from pillagerbench.metrics.formulas import Estimate, over_opponents, pairing

METRICS = ("P", "S", "D", "W")
COLUMNS = [c for m in METRICS for c in (m, f"{m}_ci")]  # a table's columns of the four: mean, then interval

# one opponent's episodes: (own points, the opponent's points, σ_blue, σ_blue's estimate)
Group = tuple[Sequence[float], Sequence[float], float | None, Estimate | None]


@dataclass(frozen=True)
class EntrantEstimate:
    episodes: int
    P: Estimate
    S: Estimate
    D: Estimate
    W: Estimate

    @classmethod
    def of(cls, metrics: dict[str, Estimate], episodes: int) -> EntrantEstimate:
        return cls(episodes, *(metrics[m] for m in METRICS))

    @classmethod
    def against(cls, own: Sequence[float], opp: Sequence[float], sigma: Estimate | None) -> EntrantEstimate:
        """Against one opponent (σ: its mean points against do_nothing, for S; None: S is empty)."""
        return cls.of(pairing(own, opp, sigma.mean if sigma else None, sigma), len(own))

    @classmethod
    def over(cls, groups: list[Group]) -> EntrantEstimate:
        """Over several opponents: P, D, W pooled, S the mean of each opponent's."""
        return cls.of(over_opponents(groups), sum(len(g[0]) for g in groups))

    def metric(self, name: str) -> Estimate:
        return {"P": self.P, "S": self.S, "D": self.D, "W": self.W}[name]

    def columns(self) -> dict[str, float | int]:
        """A table row's part: `episodes`, then each metric's mean and interval (`P`, `P_ci`, ...)."""
        row: dict[str, float | int] = {"episodes": self.episodes}
        for m in METRICS:
            row[m], row[f"{m}_ci"] = self.metric(m).mean, self.metric(m).ci
        return row
