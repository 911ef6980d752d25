"""A league played on synthetic outcomes, without a server: each episode's winner is drawn from
Bradley–Terry strengths (P(a beats b) = s_a / (s_a + s_b)). The scheduler, ratings and stop rule
are the real ones. Used by the tests and benchmarks/league_scheduler.py."""

from __future__ import annotations

import random
from itertools import permutations

from pillagerbench.league.ratings import Outcome, Rating, ranked, rate
from pillagerbench.league.schedule import Pairing, next_round, settled

SCENARIO = "sim"


def episode(p: Pairing, strengths: dict[str, float], rng: random.Random, order: tuple) -> Outcome:
    a, b = strengths[p.red], strengths[p.blue]
    red_wins = rng.random() < a / (a + b)
    return Outcome(p.scenario, p.red, p.blue, float(red_wins), float(not red_wins), order)


def scheduled(
    strengths: dict[str, float],
    *,
    seed: int = 0,
    confidence: float = 0.95,
    matches: int = 2,
    episodes: int = 2,
    budget: int = 2000,
    outcomes: list[Outcome] | None = None,
) -> tuple[list[Outcome], bool]:
    """Rounds of scheduled matches until settled or `budget` episodes; (all outcomes, settled)."""
    rng = random.Random(seed)
    outs = list(outcomes or [])
    start = len(outs)
    while len(outs) - start < budget:
        board = {SCENARIO: rate(outs, strengths)}
        pairings = next_round(board, outs, confidence, matches)
        if not pairings:
            return outs, True
        for p in pairings:
            for _ in range(episodes):
                outs.append(episode(p, strengths, rng, (len(outs),)))
    return outs, settled({SCENARIO: rate(outs, strengths)}, confidence)


def round_robin(strengths: dict[str, float], cycles: int, seed: int = 0) -> list[Outcome]:
    """Every team against every other on both sides, one episode each, `cycles` times."""
    rng = random.Random(seed)
    outs: list[Outcome] = []
    for _ in range(cycles):
        for red, blue in permutations(sorted(strengths), 2):
            outs.append(episode(Pairing(SCENARIO, red, blue), strengths, rng, (len(outs),)))
    return outs


def order(outs: list[Outcome], names: dict[str, float]) -> list[str]:
    ratings: dict[str, Rating] = rate(outs, names)
    return ranked(ratings)
