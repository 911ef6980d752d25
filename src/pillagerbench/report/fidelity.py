"""`pillagerbench fidelity RUN_DIR... [--calibration FILE|reference]`: the built-in opponents against
do_nothing beside upstream's reference scores (±25 %), and the paper's Benchmark Analysis claims
checked on a round robin (metrics/fidelity.py has the maths and the data)."""

from __future__ import annotations

import sys
from pathlib import Path

import pandas as pd

from pillagerbench.config.args import Parser
from pillagerbench.metrics import calibration as calib
from pillagerbench.metrics.fidelity import fidelity_sections
from pillagerbench.metrics.runs import ReportError, mixed_notes, mixed_title, reader_switches
from pillagerbench.metrics.verified import load_runs
from pillagerbench.report.tables import to_markdown


def tally(frame: pd.DataFrame, column: str) -> str:
    counts = frame[column].value_counts()
    return ", ".join(f"{counts.get(mark, 0)} {mark}" for mark in ("✓", "✗", "–"))


def main(argv: list[str]) -> int:
    p = Parser(prog="pillagerbench fidelity", description=__doc__.split("\n\n")[0])
    p.add_argument("runs", nargs="+", help="run directories (experiment=fidelity, calibration, round robins)")
    p.add_argument(
        "--calibration",
        default=None,
        help="a calibration.json for σ_blue (sabotage claims), or `reference`: upstream's reference scores",
    )
    reader_switches(p)
    a = p.parse_args(argv)
    try:
        runs = load_runs([Path(r) for r in a.runs], a.mix_suites, not a.no_verify)
        origin: dict = {}
        sigma, _ = calib.resolve(runs, Path(a.calibration) if a.calibration else None, origin)
    except ReportError as exc:
        print(f"pillagerbench fidelity: {exc}", file=sys.stderr)
        return 2
    table, claims, notes = fidelity_sections(runs, sigma, origin)
    mixed = mixed_title(runs)
    for note in mixed_notes(runs) + notes:
        print(note)
    if len(table):
        print(f"\nBuilt-in opponents against do_nothing (Dash & Dine ×0.1; ± is the 95 % interval){mixed}\n")
        print(to_markdown(table), end="")
        print(f"{len(table)} row(s): {tally(table, 'within_25pct')} (within ±25 % of upstream's reference)")
    if len(claims):
        print(f"\nThe paper's Benchmark Analysis claims{mixed}\n")
        print(to_markdown(claims), end="")
        print(f"{len(claims)} claim(s): {tally(claims, 'holds')}")
    if len(runs.skipped):
        print(f"{len(runs.skipped)} item(s) skipped (pillagerbench report lists them)")
    return 0
