"""How many episodes the league's scheduler needs to rank teams correctly, against a full round robin.

Two sources of episodes; the scheduler, openskill ratings and stop rule are the league's own
(pillagerbench.league.simulate):

- synthetic (default): each episode's winner is drawn from fixed Bradley–Terry strengths
  (P(a beats b) = s_a / (s_a + s_b));
- `--recorded RUN_DIR...`: a full round robin played on the server (e.g.
  `experiment=round_robin_mushroom_war` and `…_dash_and_dine`): the true order of each scenario's
  board is the one its whole round robin gives, and each episode the scheduler asks for is drawn
  (with replacement) from the recorded episodes of that pairing, so the scheduler meets the real
  teams' score distributions. Round robin cycles are drawn the same way, until they meet the same
  stop rule (or `--max-cycles`), so both reach the same confidence.

- scheduler: rounds of `--matches` matches of `--episodes` episodes until every adjacent pair is
  separated at `--confidence` (or the budget); is its final order the true one?
- round robin: every ordered pair one episode per cycle (n·(n−1) episodes a cycle); the first
  cycle from which on the order stays correct through `--max-cycles` cycles, and how many round
  robins ever meet the scheduler's stop rule within them.

    python benchmarks/league_scheduler.py --seeds 20
    python benchmarks/league_scheduler.py --recorded runs/rr_mw runs/rr_dd --seeds 20
"""

from __future__ import annotations

import argparse
import random
import statistics
from collections import defaultdict
from itertools import combinations

from pillagerbench.league.ratings import Outcome, p_above, ranked, rate
from pillagerbench.league.schedule import Pairing, settled
from pillagerbench.league.simulate import SCENARIO, order, play_scheduled, round_robin, scheduled
from pillagerbench.metrics.verified import load_runs

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


def recorded_pools(run_dirs: list[str]) -> dict[str, dict[tuple[str, str], list[tuple[float, float]]]]:
    """scenario -> (red, blue) -> the recorded (red points, blue points) of that pairing's episodes."""
    pools: dict = defaultdict(lambda: defaultdict(list))
    for r in load_runs(list(run_dirs)).episodes.itertuples():
        if r.red != r.blue:
            pools[r.scenario][(r.red, r.blue)].append((float(r.red_score), float(r.blue_score)))
    return pools


def rr_until_settled(entrants: dict[str, list[str]], draw, seed: int, confidence: float, max_cycles: int):
    """Round robin cycles drawn like the scheduler's episodes, until its boards meet the stop rule:
    (its episodes, whether it met the rule within max_cycles, its final order per scenario)."""
    rng = random.Random(seed)
    outs: list[Outcome] = []
    boards: dict = {}
    for cycle in range(max_cycles):
        for sc, names in entrants.items():
            for red in names:
                outs += [draw(Pairing(sc, red, blue), rng, (cycle, sc, red, blue)) for blue in names if blue != red]
        boards = {sc: rate([o for o in outs if o.scenario == sc], names) for sc, names in entrants.items()}
        if settled(boards, confidence):
            return outs, True, {sc: ranked(b) for sc, b in boards.items()}
    return outs, False, {sc: ranked(b) for sc, b in boards.items()}


def spread(values: list[int]) -> str:
    return f"{statistics.median(values):.0f} ({min(values)}–{max(values)})"


def recorded(args: argparse.Namespace) -> None:
    pools = recorded_pools(args.recorded)
    entrants = {sc: sorted({t for pair in pool for t in pair}) for sc, pool in pools.items()}
    full = [
        Outcome(sc, red, blue, a, b, (sc, red, blue, i))
        for sc, pool in pools.items()
        for (red, blue), scores in pool.items()
        for i, (a, b) in enumerate(scores)
    ]
    truth_boards = {sc: rate([o for o in full if o.scenario == sc], names) for sc, names in entrants.items()}
    truth_order = {sc: ranked(board) for sc, board in truth_boards.items()}
    missing = [
        f"{sc}: {r} vs {b}"
        for sc, names in entrants.items()
        for r, b in combinations(names, 2)
        if (r, b) not in pools[sc] and (b, r) not in pools[sc]
    ]
    if missing:
        raise SystemExit(f"not a full round robin, no episode of {', '.join(missing)}")

    def draw(p: Pairing, rng: random.Random, key: tuple) -> Outcome:
        pool = pools[p.scenario]
        if (p.red, p.blue) in pool:
            a, b = rng.choice(pool[(p.red, p.blue)])
        else:  # a pairing recorded with the sides the other way round only
            b, a = rng.choice(pool[(p.blue, p.red)])
        return Outcome(p.scenario, p.red, p.blue, a, b, key)

    print(f"recorded round robin: {len(full)} episodes (mirror matches left out)")
    for sc, names in truth_order.items():
        board = truth_boards[sc]
        seps = [f"{p_above(board[u], board[d]):.2f}" for u, d in zip(names, names[1:])]
        print(f"- {sc}: true order {' > '.join(names)}; P(upper above lower) of adjacent pairs {', '.join(seps)}")
    used, correct, done = [], 0, 0
    rr_used, rr_correct, rr_done = [], 0, 0
    for seed in range(args.seeds):
        rr_outs, rr_ok, rr_order = rr_until_settled(entrants, draw, 1000 + seed, args.confidence, args.max_cycles)
        rr_used.append(len(rr_outs))
        rr_done += rr_ok
        rr_correct += rr_order == truth_order
        outs, ok = play_scheduled(
            entrants,
            draw,
            seed=seed,
            confidence=args.confidence,
            matches=args.matches,
            episodes=args.episodes,
            budget=args.budget,
        )
        used.append(len(outs))
        done += ok
        got = {sc: ranked(rate([o for o in outs if o.scenario == sc], names)) for sc, names in entrants.items()}
        correct += got == truth_order
    print()
    print(
        "| episodes drawn from the recording | until the stop rule (median, range) | met it | every board in the true order |"
    )
    print("|---|---|---|---|")
    print(f"| scheduler | {spread(used)} | {done}/{args.seeds} | {correct}/{args.seeds} |")
    print(f"| round robin cycles | {spread(rr_used)} | {rr_done}/{args.seeds} | {rr_correct}/{args.seeds} |")
    print(f"\n(the recorded round robin itself: {len(full)} episodes)")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--confidence", type=float, default=0.95)
    ap.add_argument("--matches", type=int, default=2)
    ap.add_argument("--episodes", type=int, default=2)
    ap.add_argument("--max-cycles", type=int, default=40)
    ap.add_argument("--recorded", nargs="+", metavar="RUN_DIR", help="draw episodes from a recorded round robin")
    ap.add_argument("--budget", type=int, default=400, help="with --recorded: episodes at most (the league's default)")
    args = ap.parse_args()
    if args.recorded:
        recorded(args)
        return
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
