"""`pillagerbench export RUN_DIR... --out FILE [--replays]`: one results bundle (tar.gz) of run directories
(or of other bundles): their manifests, episodes, ledgers, timelines, events, chat and team artefacts,
replays with --replays, a sha256 for every file, the suite versions the episodes were played under and
every harness failure kept apart from the teams' own (rundir/bundle.py has the layout). Check one with
`pillagerbench verify FILE`; `report`, `symmetry`, `fidelity`, `calibrate` and the league read it as they read
run directories, once it passes the same checks. A bundle given to export is checked first too."""

from __future__ import annotations

from pathlib import Path

from pillagerbench.config.args import Parser
from pillagerbench.metrics.verified import load_runs, summary
from pillagerbench.rundir.bundle import write_bundle
from pillagerbench.suite.version import current


def main(argv: list[str]) -> int:
    p = Parser(prog="pillagerbench export", description=__doc__.split("\n\n")[0])
    p.add_argument("runs", nargs="+", help="run directories (experiments or plain runs) or bundles")
    p.add_argument("--out", required=True, help="the bundle to write (FILE.tar.gz)")
    p.add_argument("--replays", action="store_true", help="include the episodes' replay recordings")
    a = p.parse_args(argv)
    # a bundle carries whatever it is given and records the suites; a bundle given is verified first
    runs = load_runs(a.runs, mix_suites=True)
    out = Path(a.out)
    info = {"exported_by": current(), **summary(runs)}
    files = write_bundle([(runs.roots[name], name) for name in runs.runs], out, info, a.replays)
    harness = info["faults"]["harness_episodes"]
    print(
        f"{out}: {len(runs.runs)} run(s), {files} files, {len(runs.episodes)} episode(s) used, played under "
        f"{', '.join(runs.suites) or '–'}; {harness} episode(s) with harness failures; "
        f"{out.stat().st_size / 1e6:.1f} MB"
    )
    return 0
