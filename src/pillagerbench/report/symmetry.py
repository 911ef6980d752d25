"""`pillagerbench symmetry RUN_DIR...`: each team's points as red and as blue per pairing, with
95 % intervals and ✓/✗ for "no side effect" (metrics/symmetry.py has the maths)."""

from __future__ import annotations

import sys
from pathlib import Path

from pillagerbench.config.args import Parser
from pillagerbench.metrics.runs import ReportError, mixed_notes, reader_switches
from pillagerbench.metrics.symmetry import side_symmetry
from pillagerbench.metrics.verified import load_runs
from pillagerbench.report.tables import to_markdown


def main(argv: list[str]) -> int:
    p = Parser(prog="pillagerbench symmetry", description=__doc__.split("\n\n")[0])
    p.add_argument(
        "runs", nargs="+", help="run directories (experiment=symmetry, round robins, plain runs) or results bundles"
    )
    reader_switches(p)
    a = p.parse_args(argv)
    try:
        runs = load_runs([Path(r) for r in a.runs], a.mix_suites, not a.no_verify)
    except ReportError as exc:
        print(f"pillagerbench symmetry: {exc}", file=sys.stderr)
        return 2
    table, notes = side_symmetry(runs.episodes)
    for note in mixed_notes(runs) + notes:
        print(note)
    if len(table):
        print(to_markdown(table), end="")
        bad = (table["no_side_effect"] == "✗").sum()
        print(
            f"{len(table)} comparison(s): {(table['no_side_effect'] == '✓').sum()} ✓, {bad} ✗, "
            f"{(table['no_side_effect'] == '–').sum()} without an interval"
        )
    return 0
