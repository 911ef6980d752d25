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


def sprt_pairs(p_ahead: float, p0: float, p1: float, alpha: float, beta: float) -> float:
    """Wald's approximation of the pairs the sequential test (stats/sprt.py) expects when A is ahead in
    a share p_ahead of the pairs (won or lost, no level ones): E[N] = (L·log B + (1 − L)·log A) / E[z],
    with L the chance it accepts H0 (its operating characteristic, from h solving
    p·(p1/p0)^h + (1 − p)·((1 − p1)/(1 − p0))^h = 1) and z one pair's log-likelihood ratio."""
    up, down = math.log(p1 / p0), math.log((1 - p1) / (1 - p0))
    log_a, log_b = math.log((1 - beta) / alpha), math.log(beta / (1 - alpha))
    drift = p_ahead * up + (1 - p_ahead) * down
    if abs(drift) < 1e-9:  # the indifference point: E[N] = −log A·log B / E[z²]
        return -log_a * log_b / (p_ahead * up**2 + (1 - p_ahead) * down**2)
    h = _operating_root(p_ahead, up, down)
    accept_h0 = (math.exp(h * log_a) - 1) / (math.exp(h * log_a) - math.exp(h * log_b))
    return (accept_h0 * log_b + (1 - accept_h0) * log_a) / drift


def _operating_root(p: float, up: float, down: float) -> float:
    """The non-zero h with p·e^(h·up) + (1 − p)·e^(h·down) = 1 (its sign opposite to the drift's)."""

    def f(h: float) -> float:
        return p * math.exp(h * up) + (1 - p) * math.exp(h * down) - 1

    sign = -1.0 if p * up + (1 - p) * down > 0 else 1.0
    lo, hi = sign * 1e-6, sign * 1.0
    while f(hi) < 0:  # widen until the function turns positive again
        hi *= 2
    for _ in range(100):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
    return (lo + hi) / 2
