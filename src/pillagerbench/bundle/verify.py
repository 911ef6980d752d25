"""`pillagerbench verify FILE`: check a results bundle and name every disagreement, one line each:
every file against its sha256 (changed, missing, not listed); each manifest's suite version against
its episodes' records; the suite versions bundle.json states against the episodes' own records (and
whether each is a released version, and this installation's); each finished episode's scores against
its recorded score timeline, its headline score, its winner and its episode.json; the harness failures
bundle.json counts against the records. The checks are metrics/verified.py's, the same that every
reader of a bundle runs first. Exit 0 when all agree, 1 when something disagrees, 2 when the file is not
a readable bundle."""

from __future__ import annotations

from pathlib import Path

from pillagerbench.config.args import Parser
from pillagerbench.metrics.verified import bundle_problems


def main(argv: list[str]) -> int:
    p = Parser(prog="pillagerbench verify", description=__doc__.split("\n\n")[0])
    p.add_argument("bundle", help="a results bundle (pillagerbench export)")
    a = p.parse_args(argv)
    problems, facts = bundle_problems(Path(a.bundle))
    for line in facts:
        print(line)
    for line in problems:
        print(f"disagrees: {line}")
    print(f"{a.bundle}: {'verified' if not problems else f'{len(problems)} disagreement(s)'}")
    return 1 if problems else 0
