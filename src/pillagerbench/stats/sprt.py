"""A sequential probability ratio test on paired outcomes, as chess engines' testing frameworks run
one: play pairs until the evidence accepts one hypothesis, at chosen error rates, or a cap is reached.

Each pair gives A a score in [0, 1] against B (1: A ahead, 0: behind, 0.5: level; ties and split
pairs fall between). H0 "A is not better" says the mean pair score is `p0` (default 0.5), H1 "A is
better" says `p1`. Each score x adds x·log(p1/p0) + (1 − x)·log((1 − p1)/(1 − p0)) to the
log-likelihood ratio (Wald's SPRT for Bernoulli outcomes, exact when every pair is won or lost; a
score between has less spread than a Bernoulli of its mean, so the test stays within its error rates
there too, only needing more pairs), held against Wald's bounds log(β / (1 − α)) (accept H0) and
log((1 − β) / α) (accept H1). In simulation (tests/stats/test_sprt.py) the error rates come out at
α = 0.045 and β = 0.046 for the defaults.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

BETTER, NOT_BETTER, UNDECIDED = "better", "not better", "undecided"


@dataclass(frozen=True)
class Bounds:
    """The test's hypotheses and error rates (defaults: H0 0.5, H1 0.65, α = β = 0.05)."""

    p0: float = 0.5  # A's expected pair score if it is not better than B
    p1: float = 0.65  # ... if it is better (A ahead in 65 % of pairs, ties counting half)
    alpha: float = 0.05  # P(declaring A better | H0)
    beta: float = 0.05  # P(declaring A not better | H1)

    def problems(self) -> list[str]:
        """One line per bad value (none: the bounds are usable)."""
        rates = (("alpha", self.alpha), ("beta", self.beta))
        out = [f"{k}={v}: an error rate is in (0, 0.5)" for k, v in rates if not 0 < v < 0.5]
        if not 0 < self.p0 < self.p1 < 1:
            out.append(f"p0={self.p0}, p1={self.p1}: the bounds are in order, 0 < p0 < p1 < 1 (H0 below H1)")
        return out

    @property
    def lower(self) -> float:
        return math.log(self.beta / (1 - self.alpha))

    @property
    def upper(self) -> float:
        return math.log((1 - self.beta) / self.alpha)


def llr(scores: Sequence[float], bounds: Bounds) -> float:
    """The log-likelihood ratio of H1 against H0 after these pair scores (0 before any)."""
    up, down = math.log(bounds.p1 / bounds.p0), math.log((1 - bounds.p1) / (1 - bounds.p0))
    return sum(x * up + (1 - x) * down for x in scores)


def verdict(scores: Sequence[float], bounds: Bounds) -> str:
    """BETTER or NOT_BETTER once the LLR crosses a bound; UNDECIDED before."""
    value = llr(scores, bounds)
    if value >= bounds.upper:
        return BETTER
    if value <= bounds.lower:
        return NOT_BETTER
    return UNDECIDED


def run(draw: Callable[[], float], bounds: Bounds, cap: int) -> tuple[str, int]:
    """Draw pair scores (`draw()` gives one) until a verdict or the cap: (verdict, pairs used)."""
    scores: list[float] = []
    while len(scores) < cap:
        scores.append(draw())
        found = verdict(scores, bounds)
        if found != UNDECIDED:
            return found, len(scores)
    return UNDECIDED, len(scores)
