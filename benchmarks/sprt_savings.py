"""How many episodes the sequential test saves (issue 41's benchmark, simulated).

For every two built-in opponents of a scenario, their points against do_nothing as the suite's own
reference figures give them (mean, and the spread behind the 95 % interval, clean scoring) make a
normal model of one episode each; a pair (the same layout and seed for both) scores 1 for the one
ahead. The sequential test (stats/sprt.py, default bounds: H0 0.5, H1 0.65, α = β = 0.05) is run on
simulated pairs `--runs` times; its mean episodes are set against a fixed-size one-sided test of the
same hypotheses and error rates (stats/sample_size.py). Prints a table and one JSON line.

    python benchmarks/sprt_savings.py            # target: SPRT's mean episodes <= 50 % of the fixed design
    python benchmarks/sprt_savings.py --runs 4000 --seed 7
"""

from __future__ import annotations

import argparse
import itertools
import json
import random
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))
from pillagerbench.stats.sample_size import fixed_test, sd_of
from pillagerbench.stats.sprt import BETTER, Bounds, run
from pillagerbench.suite.figures import reference_figures


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=2000)
    ap.add_argument("--seed", type=int, default=41)
    a = ap.parse_args()
    bounds = Bounds()
    fixed_pairs = fixed_test(0.5, bounds.p1 - bounds.p0, bounds.alpha, bounds.beta)
    rng = random.Random(a.seed)
    rows = []
    for scenario, teams in reference_figures().scenarios.items():
        model = {t: (v["clean"].mean, sd_of(v["clean"].ci, v["clean"].n)) for t, v in teams.items()}
        for x, y in itertools.combinations(model, 2):
            better, worse = (x, y) if model[x][0] >= model[y][0] else (y, x)
            (mb, sb), (mw, sw) = model[better], model[worse]

            def pair(mb: float = mb, sb: float = sb, mw: float = mw, sw: float = sw) -> float:
                return float(rng.gauss(mb, sb) > rng.gauss(mw, sw))

            found = [run(pair, bounds, cap=10 * fixed_pairs) for _ in range(a.runs)]
            mean_pairs = sum(n for _, n in found) / a.runs
            rows.append(
                {
                    "scenario": scenario,
                    "a": better,
                    "b": worse,
                    "difference": round(mb - mw, 2),
                    "said_better": round(sum(v == BETTER for v, _ in found) / a.runs, 3),
                    "sprt_episodes": round(2 * mean_pairs, 1),
                    "fixed_episodes": 2 * fixed_pairs,
                    "ratio": round(mean_pairs / fixed_pairs, 3),
                }
            )
    for r in rows:
        print(
            f"{r['scenario']:<14} {r['a']:>14} vs {r['b']:<14} Δ {r['difference']:>6}  said better {r['said_better']:.3f}"
            f"  SPRT {r['sprt_episodes']:>6} episodes  fixed {r['fixed_episodes']}  ratio {r['ratio']:.3f}"
        )
    mean_ratio = sum(r["ratio"] for r in rows) / len(rows)
    print(
        json.dumps(
            {
                "pairs_of_opponents": len(rows),
                "fixed_episodes": 2 * fixed_pairs,
                "mean_ratio": round(mean_ratio, 3),
                "max_ratio": max(r["ratio"] for r in rows),
            }
        )
    )


if __name__ == "__main__":
    main()
