"""A league played on synthetic outcomes, without a server: each episode's winner is drawn from
Bradley–Terry strengths (P(a beats b) = s_a / (s_a + s_b)). The scheduler, ratings and stop rule
are the real ones. Used by the tests and benchmarks/league_scheduler.py."""

from __future__ import annotations

import random
from collections.abc import Callable
from itertools import permutations

from pillagerbench.league.ratings import Outcome, Rating, ranked, rate
from pillagerbench.league.schedule import Pairing, next_round, settled

SCENARIO = "sim"


def episode(p: Pairing, strengths: dict[str, float], rng: random.Random, order: tuple) -> Outcome:
    a, b = strengths[p.red], strengths[p.blue]
    red_wins = rng.random() < a / (a + b)
    return Outcome(p.scenario, p.red, p.blue, float(red_wins), float(not red_wins), order)


Draw = Callable[[Pairing, random.Random, tuple], Outcome]


def play_scheduled(
    entrants: dict[str, list[str]],
    draw: Draw,
    *,
    seed: int = 0,
    confidence: float = 0.95,
    matches: int = 2,
    episodes: int = 2,
    budget: int = 2000,
    outcomes: list[Outcome] | None = None,
) -> tuple[list[Outcome], bool]:
    """Rounds of scheduled matches on every scenario's board (`entrants`: scenario -> names), each
    episode's outcome from `draw`, until settled or `budget` episodes; (all outcomes, settled)."""
    rng = random.Random(seed)
    outs = list(outcomes or [])
    start = len(outs)

    def boards() -> dict[str, dict[str, Rating]]:
        return {sc: rate([o for o in outs if o.scenario == sc], names) for sc, names in entrants.items()}

    while len(outs) - start < budget:
        pairings = next_round(boards(), outs, confidence, matches)
        if not pairings:
            return outs, True
        for p in pairings:
            for _ in range(episodes):
                outs.append(draw(p, rng, (len(outs),)))
    return outs, settled(boards(), confidence)


def scheduled(strengths: dict[str, float], **kwargs) -> tuple[list[Outcome], bool]:
    """play_scheduled on one board of Bradley-Terry teams."""
    return play_scheduled({SCENARIO: list(strengths)}, lambda p, rng, o: episode(p, strengths, rng, o), **kwargs)


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
