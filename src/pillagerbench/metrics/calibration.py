"""σ_blue, the reference for the sabotage metric S: the mean score of each built-in opponent (blue)
when the red team is do_nothing, from real episodes stored with the results.

    pillagerbench calibrate [key=value ...]        play experiment=calibration, write its calibration.json
    pillagerbench calibrate RUN_DIR... [--out F]   compute it from runs that have do_nothing-red series
                                                   (e.g. a round robin), write RUN_DIR/calibration.json;
                                                   --mix-suites allows runs of different suite versions;
                                                   --no-verify reads a bundle that fails its checks

calibration.json: {"created", "sources": [run dirs], "scenarios": {scenario: {"version", "episode_length",
"opponents": {entrant: {"sigma_blue", "ci", "std", "n"}}}}}, scores unscaled (the report scales them); an
opponent is its entrant's label (metrics/entrants.py): a built-in team's is its name, as in upstream's reference.
`pillagerbench run experiment=... calibration=FILE` copies the file into the new run directory.
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path

import numpy as np
import pandas as pd

from pillagerbench.config.args import Parser
from pillagerbench.config.sides import other_side
from pillagerbench.metrics.columns import Col
from pillagerbench.metrics.formulas import SCORE_SCALE, Estimate, mean_ci
from pillagerbench.metrics.reference import REFERENCE_CALIBRATION, REFERENCE_SCORES
from pillagerbench.metrics.runs import ReportError, Runs, beside, mixed_notes, reader_switches
from pillagerbench.metrics.verified import load_runs
from pillagerbench.rundir import names

CALIBRATION = names.CALIBRATION
FROM_RUNS = "the do_nothing-red episodes of these runs"  # where σ_blue came from, in resolve's notes
REFERENCE_FALLBACK = (
    "upstream's reference scores, as these runs carry no calibration for it "
    "(the same as --calibration reference; pillagerbench calibrate measures your own)"
)


def against_do_nothing(df: pd.DataFrame, side: str = "blue"):
    """(scenario, entrant, episodes) for every built-in team or other entrant that played `side` against a
    do_nothing team on the other side, in ordinary series (shared by σ_blue and the fidelity check); a
    built-in team's entrant is its name."""
    if not len(df):
        return
    other = other_side(side)
    ref = df[(df[Col.team(other)] == "do_nothing") & df[Col.GROUP].isna()]
    yield from ((sc, team, g) for (sc, team), g in ref.groupby([Col.SCENARIO, Col.name(side)], sort=False))


def opponent_groups(df: pd.DataFrame, sigma: dict) -> list:
    """Per opponent (blue entrant) of the red rows in df: (red scores, blue scores, σ_blue, σ estimate),
    the input of formulas.over_opponents."""
    out = []
    for (scenario, blue), g in df.groupby([Col.SCENARIO, Col.BLUE], sort=False):
        s = sigma.get((scenario, blue))
        out.append((g[Col.RED_SCORE].to_numpy(), g[Col.BLUE_SCORE].to_numpy(), s.mean if s else None, s))
    return out


def calibration_from_runs(runs: Runs) -> dict:
    scenarios: dict[str, dict] = {}
    for scenario, blue, g in against_do_nothing(runs.episodes, "blue"):
        e = mean_ci(g[Col.BLUE_RAW])
        entry = scenarios.setdefault(
            scenario,
            {
                "version": str(g[Col.VERSION].iloc[0]),
                "episode_length": float(g[Col.EPISODE_LENGTH].iloc[0]),
                "opponents": {},
            },
        )
        entry["opponents"][blue] = {
            "sigma_blue": e.mean,
            "ci": None if math.isnan(e.ci) else e.ci,
            "std": float(np.std(g[Col.BLUE_RAW], ddof=1)) if e.n > 1 else None,
            "n": e.n,
        }
    return {
        "created": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        "sources": [str(r) for r in runs.runs],
        "suites": runs.suites,  # more than one only with --mix-suites
        "notes": mixed_notes(runs),  # mixed suites, bundles read without their checks (--no-verify)
        "scenarios": scenarios,
    }


def read_calibration(path: Path) -> dict:
    data = json.loads(Path(path).read_text())
    if "scenarios" not in data:
        raise ReportError(f"{path}: not a calibration file (no 'scenarios'; make one with pillagerbench calibrate)")
    return data


def reference_calibration(want: dict[str, tuple[str, float]]) -> dict:
    """upstream's reference scores as a calibration (unscaled) for the runs' scenario versions."""
    return {
        "scenarios": {
            sc: {
                "version": version,
                "episode_length": length,
                "opponents": {
                    team: {"sigma_blue": v / SCORE_SCALE.get(sc, 1.0), "ci": None, "n": 0}
                    for team, v in REFERENCE_SCORES[sc].items()
                },
            }
            for sc, (version, length) in want.items()
            if sc in REFERENCE_SCORES
        }
    }


def explicit_calibration(explicit: Path, want: dict[str, tuple[str, float]]) -> dict:
    """--calibration: a calibration.json, or `reference` for upstream's reference scores."""
    if str(explicit) == REFERENCE_CALIBRATION:
        return reference_calibration(want)
    if not Path(explicit).is_file():
        raise ReportError(
            f"--calibration {explicit}: no such file; give a calibration.json (pillagerbench calibrate writes one) "
            f"or --calibration {REFERENCE_CALIBRATION} for upstream's reference scores"
        )
    return read_calibration(explicit)


def resolve(
    runs: Runs, explicit: Path | None = None, origin: dict | None = None, fallback: bool = False
) -> tuple[dict, list[str]]:
    """σ_blue per (scenario, opponent team) as scaled Estimates, and notes on where each came from
    (`origin`, if given, gets (scenario, team) -> where).

    Order: an explicit file (must match the runs' scenario versions and episode lengths; `reference`:
    upstream's reference scores, as its analysis used them), then
    calibration.json files stored in the runs, then do_nothing-red episodes among the runs; with
    `fallback` (the report), a scenario that none of these covers gets upstream's reference scores."""
    df = runs.episodes
    want = (
        {}
        if not len(df)
        else {
            sc: (str(g[Col.VERSION].iloc[0]), float(g[Col.EPISODE_LENGTH].iloc[0]))
            for sc, g in df.groupby(Col.SCENARIO)
        }
    )
    sources = (
        ([(explicit, explicit_calibration(explicit, want), True)] if explicit else [])
        + [(p, read_calibration(p), False) for p in runs.calibration_files]
        + [(FROM_RUNS, calibration_from_runs(runs), False)]
    )
    table: dict[tuple[str, str], Estimate] = {}
    notes: list[str] = []
    for where, cal, strict in sources:
        _use(where, cal, strict, want, table, notes, origin)
    if fallback:
        bare = {sc: v for sc, v in want.items() if not any(key[0] == sc for key in table)}
        _use(REFERENCE_FALLBACK, reference_calibration(bare), False, want, table, notes, origin)
    return table, notes


def _use(where, cal: dict, strict: bool, want: dict, table: dict, notes: list[str], origin: dict | None) -> None:
    """Add a calibration's σ_blue to `table` where it has none yet (resolve's order decides)."""
    for scenario, entry in cal["scenarios"].items():
        if scenario not in want:
            continue
        have = (str(entry.get("version")), float(entry.get("episode_length", 0)))
        if have != want[scenario]:
            msg = (
                f"calibration {where} for {scenario} is of version {have[0]} with {have[1]:g} s episodes; "
                f"the runs are version {want[scenario][0]} with {want[scenario][1]:g} s episodes"
            )
            if strict:
                raise ReportError(msg)
            notes.append(msg + ": not used")
            continue
        scale = SCORE_SCALE.get(scenario, 1.0)
        used = []
        for team, o in entry["opponents"].items():
            if (scenario, team) in table or o.get("sigma_blue") is None:
                continue
            ci = o.get("ci")
            table[(scenario, team)] = Estimate(
                float(o["sigma_blue"]) * scale,
                float("nan") if ci is None else float(ci) * scale,
                int(o.get("n", 0)),
            )
            used.append(f"{team} (n={o['n']})" if o.get("n") else team)
            if origin is not None:
                origin[(scenario, team)] = where
        if used:
            notes.append(f"σ_blue for {scenario} from {where}: {', '.join(used)}")


def main(argv: list[str]) -> int:
    dirs = [a for a in argv if "=" not in a and not a.startswith("-")]
    if dirs:
        p = Parser(prog="pillagerbench calibrate")
        p.add_argument("runs", nargs="+")
        p.add_argument(
            "--out",
            default=None,
            help="file to write (default: FIRST_RUN/calibration.json; beside a bundle: BUNDLE_calibration.json)",
        )
        reader_switches(p)
        a = p.parse_args(argv)
        runs = load_runs(a.runs, a.mix_suites, not a.no_verify)
        out = Path(a.out) if a.out else beside(Path(a.runs[0]), CALIBRATION)
    else:  # play the calibration experiment first
        from pillagerbench.config.validate import load_run
        from pillagerbench.experiments.runner import main_experiment, make_experiment_dir

        overrides = list(argv)
        if not any(o.startswith(("experiment=", "resume=")) for o in overrides):
            overrides.insert(0, "experiment=calibration")
        cfg = load_run(overrides, teams=False)
        if not cfg.resume and not cfg.run_dir:
            made = str(make_experiment_dir(cfg))
            overrides.append(f"run_dir={made}")
            cfg = cfg.updated({"run_dir": made})
        code = main_experiment(cfg, overrides)
        if code:
            return code
        run_dir = Path(cfg.resume or cfg.run_dir or "")
        runs = load_runs([run_dir])
        out = run_dir / CALIBRATION
    cal = calibration_from_runs(runs)
    if not cal["scenarios"]:
        raise ReportError("no finished do_nothing-red episodes in these runs: nothing to calibrate")
    out.write_text(json.dumps(cal, indent=1))
    for note in mixed_notes(runs):
        print(note)
    for scenario, entry in cal["scenarios"].items():
        for team, o in entry["opponents"].items():
            print(f"{scenario:<14} {team:<14} σ_blue = {o['sigma_blue']:.2f} (n={o['n']})")
    for where, why in runs.skipped:
        print(f"skipped {where}: {why}")
    print(f"calibration: {out}")
    return 0
