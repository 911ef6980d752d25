"""The plan's answer to "how many?" (`plan=true`, issue 41): the episodes, and at this run's cost per
episode the dollars, that a question needs, from how much one episode's points spread in the suite's
reference figures (suite/figures.py: the widest of the scenario's built-in opponents, a cautious
figure):

- a team's mean points to ± `plan_width` (95 %): (z·σ / width)² episodes;
- two entrants `plan_difference` points apart against one opponent, told apart by a fixed-size
  one-sided test at α = β = 0.05 (each entrant's episodes: the difference of two means spreads σ·√2),
  and by `pillagerbench compare` with its default bounds, whose sequential test expects the pairs of
  Wald's approximation when A is ahead in Φ(difference / (σ·√2)) of the pairs.
"""

from __future__ import annotations

import math
from statistics import NormalDist

from pillagerbench.stats.sample_size import fixed_test, for_half_width, sprt_pairs
from pillagerbench.stats.sprt import Bounds
from pillagerbench.suite.figures import widest_spread


def _usd(episodes: int, per_episode: tuple[float, float] | None) -> str:
    if not per_episode or per_episode[1] <= 0:
        return ""
    lo, hi = (episodes * c for c in per_episode)
    return f" (${lo:,.2f} to ${hi:,.2f} at this run's LLM cost per episode)"


def how_many(
    scenarios: list[str], width: float, difference: float, per_episode: tuple[float, float] | None = None
) -> list[str]:
    """One line per scenario with reference figures."""
    out, b = [], Bounds()
    for sc in scenarios:
        sd = widest_spread(sc)
        if sd is None:
            continue
        mean_n = for_half_width(sd, width)
        fixed_n = fixed_test(sd * math.sqrt(2), difference, b.alpha, b.beta)
        ahead = NormalDist().cdf(difference / (sd * math.sqrt(2)))
        pairs = math.ceil(sprt_pairs(ahead, b.p0, b.p1, b.alpha, b.beta))
        out.append(
            f"how many ({sc}; one episode's points spread σ ≈ {sd:.1f}, the widest of the suite's reference "
            f"figures): ± {width:g} points on a mean: {mean_n} episodes{_usd(mean_n, per_episode)}; two entrants "
            f"{difference:g} points apart against one opponent: {fixed_n} episodes each for a fixed-size test at "
            f"α = β = {b.alpha:g}{_usd(2 * fixed_n, per_episode)}, about {2 * pairs} in all with `pillagerbench "
            f"compare` (A ahead in {ahead:.0%} of pairs; Wald's approximation){_usd(2 * pairs, per_episode)}"
        )
    return out
