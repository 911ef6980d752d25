"""What metrics finds in the runs, finished, for the report: the runs read (each bundle checked), σ_blue,
every table of estimates (metrics/estimates.py, each row an `EntrantEstimate`) and the notes metrics owes
a reader. `report/build.py` takes it once and only formats it."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from pillagerbench.metrics import calibration as calib
from pillagerbench.metrics import estimates as E
from pillagerbench.metrics.faults import fault_note, faults_table
from pillagerbench.metrics.fidelity import fidelity_sections
from pillagerbench.metrics.generalization import unseen_arenas
from pillagerbench.metrics.paired import by_entrant, differences
from pillagerbench.metrics.runs import Runs, mixed_notes, mixed_title
from pillagerbench.metrics.symmetry import side_symmetry
from pillagerbench.metrics.verified import load_runs


@dataclass
class Findings:
    runs: Runs
    sigma: dict  # (scenario, opponent) -> σ_blue's Estimate
    main: pd.DataFrame  # the used episodes of ordinary series (not evaluation groups)
    view: pd.DataFrame  # main's episodes from each side (estimates.team_view)
    summary: pd.DataFrame
    per_scenario: pd.DataFrame
    per_team: pd.DataFrame
    pairs: pd.DataFrame
    grouped: pd.DataFrame
    differences: pd.DataFrame
    symmetry: pd.DataFrame
    one_order: list[str]  # side symmetry's notes on pairings played in one order only
    fidelity: pd.DataFrame
    claims: pd.DataFrame
    arenas: pd.DataFrame  # unseen arenas (empty without episodes on generated layouts)
    curve: pd.DataFrame
    calibration: pd.DataFrame
    lag: pd.DataFrame
    faults: pd.DataFrame
    skipped: pd.DataFrame
    calibration_notes: list[str]  # where each σ_blue came from
    fidelity_notes: list[str]
    mixed_notes: list[str]  # mixed suite versions, bundles not verified
    fault_notes: list[str]
    title: str  # what every table's title adds (mixed suites, not verified)


def find(
    run_dirs: list[str | Path], calibration: Path | None = None, mix_suites: bool = False, verify: bool = True
) -> Findings:
    """The runs read and everything the report shows of them, computed."""
    runs = load_runs(run_dirs, mix_suites, verify)
    origin: dict = {}
    sigma, notes = calib.resolve(runs, calibration, origin, fallback=True)
    main = E.main_episodes(runs.episodes)
    symmetry, one_order = side_symmetry(main)
    fidelity, claims, fidelity_notes = fidelity_sections(runs, sigma, origin)
    plan = E.planned(runs.series, runs.episodes, runs.spoiled)
    return Findings(
        runs=runs,
        sigma=sigma,
        main=main,
        view=E.team_view(main),
        summary=E.summary(main, sigma, runs.ledger, plan=plan),
        per_scenario=E.summary(main, sigma, runs.ledger, by_scenario=True, plan=plan),
        per_team=E.per_team(main, sigma),
        pairs=E.pairings(main, sigma),
        grouped=E.groups(runs.episodes, sigma),
        differences=differences(by_entrant(main)),
        symmetry=symmetry,
        one_order=one_order,
        fidelity=fidelity,
        claims=claims,
        arenas=unseen_arenas(main, sigma),
        curve=E.learning_curve(main),
        calibration=E.calibration(sigma),
        lag=E.lagged(runs.spoiled),
        faults=faults_table(runs.faults),
        skipped=E.skipped(runs.skipped),
        calibration_notes=notes,
        fidelity_notes=fidelity_notes,
        mixed_notes=mixed_notes(runs),
        fault_notes=fault_note(runs.faults),
        title=mixed_title(runs),
    )
