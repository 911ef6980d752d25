"""The generalization gap: a metric on layouts a team has never seen minus the same metric on the
paper's layout (issue 29; docs/layouts.md).

Unseen layouts are those of the held-out splits (UNSEEN): `test` layouts are drawn fresh for every
episode, `dev` layouts are public seeds for tuning (unseen by the paper's map, not by a tuner). The
gap's 95 % interval is that of a difference of two independent means from their standard errors,
with Welch–Satterthwaite degrees of freedom (formulas.welch_half_width, as side symmetry's).
"""

from __future__ import annotations

import math

from pillagerbench.metrics.formulas import Estimate, welch_half_width

UNSEEN = ("test", "dev")  # the splits of generated layouts, in the order they are reported


def gap(unseen: Estimate, paper: Estimate) -> Estimate:
    """unseen − paper, with a 95 % interval when both have one (else nan)."""
    diff = unseen.mean - paper.mean
    n = unseen.n + paper.n
    if min(unseen.n, paper.n) < 2 or math.isnan(unseen.se) or math.isnan(paper.se):
        return Estimate(diff, float("nan"), n)
    return Estimate(diff, welch_half_width(unseen.se, unseen.n, paper.se, paper.n), n)
