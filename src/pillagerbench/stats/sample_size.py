"""How many episodes a question needs, from a spread (a standard deviation) that earlier episodes
showed: to narrow a mean's 95 % interval to ± a half-width, or for a fixed-size one-sided test to
tell a difference at error rates α and β (the number a sequential test is measured against)."""

from __future__ import annotations

import math
from statistics import NormalDist

Z = NormalDist()


def for_half_width(sd: float, half_width: float, confidence: float = 0.95) -> int:
    """Episodes for a mean's interval of ± half_width (normal approximation)."""
    z = Z.inv_cdf((1 + confidence) / 2)
    return max(2, math.ceil((z * sd / half_width) ** 2))


def fixed_test(sd: float, difference: float, alpha: float = 0.05, beta: float = 0.05) -> int:
    """Observations a fixed-size one-sided z test needs to tell a mean `difference` apart from none
    at error rates alpha (false alarm) and beta (miss), each observation of spread sd."""
    return max(1, math.ceil(((Z.inv_cdf(1 - alpha) + Z.inv_cdf(1 - beta)) * sd / difference) ** 2))


def sd_of(half_width: float, n: int, confidence: float = 0.95) -> float:
    """The spread behind a reported interval (± half_width over n episodes)."""
    return half_width * math.sqrt(n) / Z.inv_cdf((1 + confidence) / 2)
