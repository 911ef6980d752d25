"""The suite's own reference figures (src/pillagerbench/suite/reference_figures.json) from a fidelity run
played under this installation's suite version: each built-in opponent's points (blue) against
do_nothing, mean and 95 % interval per scoring, as `pillagerbench fidelity` computes them.

    .venv/bin/pillagerbench run experiment=fidelity scoring=upstream protocol=upstream parallel=4 run_dir=RUN
    .venv/bin/python scripts/reference_figures.py RUN --source "RUN at COMMIT: the command above, seed=S"

Refuses a run of another suite version, one with an episode flagged for lag or failed, and one that
lacks an opponent. Rewrites the JSON file and prints the rows of docs/suite-versions.md's table.
"""

from __future__ import annotations

import argparse
import json
import sys
from datetime import date
from pathlib import Path

from pillagerbench.experiments import builtin_teams
from pillagerbench.metrics.fidelity import fidelity_table
from pillagerbench.metrics.reference import REFERENCE_CONDITIONS
from pillagerbench.metrics.verified import load_runs
from pillagerbench.suite import version as suite
from pillagerbench.suite.conditions import stamp
from pillagerbench.suite.figures import FIGURES

TITLES = {"mushroom_war": "Mushroom War", "dash_and_dine": "Dash & Dine"}


def figures(run: Path) -> dict[str, dict]:
    runs = load_runs([run])
    # the references' conditions, with upstream's scoring so that each episode records both scorings
    here = stamp(suite.current()["label"], {**REFERENCE_CONDITIONS, "scoring": "upstream"})
    if runs.suites != [here]:
        sys.exit(f"reference_figures: {run} was played under {', '.join(runs.suites)}, this installation is {here}")
    df = runs.episodes
    if df["lagged"].any() or runs.skipped:
        sys.exit(f"reference_figures: {run} has episodes flagged for lag or skipped: {runs.skipped[:3]}")
    table, _ = fidelity_table(df)
    out: dict[str, dict] = {}
    for row in table[table["side"] == "blue"].itertuples():
        by = out.setdefault(row.scenario, {}).setdefault(row.opponent, {})
        by[row.scoring] = {"mean": round(row.points, 2), "ci": round(row.points_ci, 2), "n": int(row.episodes)}
    for scenario in TITLES:
        missing = set(builtin_teams(scenario)) - {"do_nothing"} - set(out.get(scenario, {}))
        if missing:
            sys.exit(f"reference_figures: {run} has no {scenario} episodes of {', '.join(sorted(missing))}")
    return out


def dump(data: dict) -> str:
    """JSON with an indent of one, each opponent's figures on one line."""
    rows = {f"@{sc}/{team}@": by for sc, teams in data["scenarios"].items() for team, by in teams.items()}
    outline = {
        **data,
        "scenarios": {sc: {team: f"@{sc}/{team}@" for team in teams} for sc, teams in data["scenarios"].items()},
    }
    text = json.dumps(outline, indent=1, ensure_ascii=False)
    for mark, by in rows.items():
        text = text.replace(json.dumps(mark), json.dumps(by))
    return text + "\n"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", type=Path)
    ap.add_argument("--source", required=True, help="where the figures come from: run, commit, command")
    a = ap.parse_args()
    scenarios = figures(a.run)
    data = json.loads(FIGURES.read_text())
    name = suite.current()["name"]
    data.update(
        suite=name,
        status=f"measured under {suite.current()['label']} ({date.today()})",
        source=a.source,
        scenarios=scenarios,
    )
    FIGURES.write_text(dump(data))
    for scenario, teams in scenarios.items():
        for team, by in teams.items():
            cells = " | ".join(f"{by[s]['mean']:.2f} ± {by[s]['ci']:.2f}" for s in ("clean", "upstream"))
            print(f"| {TITLES[scenario]} | {team} | {cells} |")


if __name__ == "__main__":
    main()
