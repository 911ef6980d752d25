"""How many episodes the league's scheduler needs to rank teams correctly, against a full round robin.

A SIMULATION, not a measurement on the server: each episode's winner is drawn from fixed
Bradley–Terry strengths (P(a beats b) = s_a / (s_a + s_b)); the scheduler, openskill ratings
and stop rule are the league's own (pillagerbench.league.simulate). There is no recorded round
robin of the built-in teams yet; the real comparison on the server is left to do.

- scheduler: rounds of `--matches` matches of `--episodes` episodes until every adjacent pair is
  separated at `--confidence` (or the budget); is its final order the true one?
- round robin: every ordered pair one episode per cycle (n·(n−1) episodes a cycle); the first
  cycle from which on the order stays correct through `--max-cycles` cycles, and how many round
  robins ever meet the scheduler's stop rule within them.

    python benchmarks/league_scheduler.py --seeds 20
"""

from __future__ import annotations

import argparse
import statistics

from pillagerbench.league.ratings import rate
from pillagerbench.league.schedule import settled
from pillagerbench.league.simulate import SCENARIO, order, round_robin, scheduled

# Mushroom War's five (do_nothing + the four built-ins), strengths doubling down the ladder;
# and nine teams (the built-ins of both scenarios as one board) the same way.
LEAGUES = {
    "5 teams": {"slimy": 16.0, "aggressive": 8.0, "balanced": 4.0, "passive": 2.0, "do_nothing": 0.25},
    "9 teams": {f"t{i}": 2.0 ** (8 - i) for i in range(8)} | {"do_nothing": 0.25},
}


def truth(strengths: dict[str, float]) -> list[str]:
    return sorted(strengths, key=lambda n: -strengths[n])


def rr_cycles(strengths: dict[str, float], seed: int, confidence: float, max_cycles: int) -> tuple[int, bool]:
    """(first cycle from which the order stays correct (0: never), whether the stop rule is ever met)."""
    outs = round_robin(strengths, max_cycles, seed)
    per = len(strengths) * (len(strengths) - 1)
    stays, stopped = 0, False
    for c in range(1, max_cycles + 1):
        part = outs[: c * per]
        if order(part, strengths) != truth(strengths):
            stays = 0
            continue
        stays = stays or c
        stopped = stopped or settled({SCENARIO: rate(part, strengths)}, confidence)
    return stays, stopped


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--confidence", type=float, default=0.95)
    ap.add_argument("--matches", type=int, default=2)
    ap.add_argument("--episodes", type=int, default=2)
    ap.add_argument("--max-cycles", type=int, default=40)
    args = ap.parse_args()
    print(
        "| league | scheduler: episodes to stop (median, range) | scheduler: order correct | round robin: episodes "
        "until the order stays correct (median, range) | round robin: never stays correct | round robin: ever meets "
        "the stop rule |"
    )
    print("|---|---|---|---|---|---|")
    for label, strengths in LEAGUES.items():
        per = len(strengths) * (len(strengths) - 1)
        used, correct, rr_stays, rr_stop = [], 0, [], 0
        for seed in range(args.seeds):
            outs, _ = scheduled(
                strengths,
                seed=seed,
                confidence=args.confidence,
                matches=args.matches,
                episodes=args.episodes,
                budget=per * args.max_cycles,
            )
            used.append(len(outs))
            correct += order(outs, strengths) == truth(strengths)
            stays, stop = rr_cycles(strengths, 1000 + seed, args.confidence, args.max_cycles)
            rr_stays += [stays * per] if stays else []
            rr_stop += stop
        never = args.seeds - len(rr_stays)
        stays_text = f"{statistics.median(rr_stays):.0f} ({min(rr_stays)}–{max(rr_stays)})" if rr_stays else "–"
        print(
            f"| {label} | {statistics.median(used):.0f} ({min(used)}–{max(used)}) | {correct}/{args.seeds} | "
            f"{stays_text} | {never}/{args.seeds} | {rr_stop}/{args.seeds} |"
        )


if __name__ == "__main__":
    main()
