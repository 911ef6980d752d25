"""`pillagerbench report RUN_DIR... [--out DIR] [--calibration FILE|reference]`: the paper's tables and
figures from run directories (experiments or plain runs), as Markdown, CSV, PNG and one HTML page.

Everything is written under --out (replay pages included); the run directories are only read.
The page opens with the runs' provenance (revision, seeds, episode length, models, scoring and
protocol, from their manifests) and a table of contents; a section with nothing in it is left off
the page (its file is still written, so scripts can rely on the set of files). A value resting on
one episode is marked "n = 1" (it has no interval). Dash & Dine scores are scaled ×0.1 as in the
paper. σ_blue (for S) comes from --calibration (`reference`: upstream's reference scores), else
from calibration.json files stored in the runs, else from do_nothing-red episodes among the runs,
else, for a scenario none of these covers, from upstream's reference scores (a note says so).
Skipped episodes are listed with the reason in skipped.md and on the page; runs of different
scenario versions are refused.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pandas as pd

from pillagerbench.config.args import Parser
from pillagerbench.metrics.columns import Col
from pillagerbench.metrics.estimates import ALL, scenario_order
from pillagerbench.metrics.findings import Findings, find
from pillagerbench.metrics.runs import ReportError, beside, reader_switches
from pillagerbench.report import comparison, html, plots, replays
from pillagerbench.report import generalization as unseen
from pillagerbench.report.provenance import provenance
from pillagerbench.report.sections import Section, figure, table

DIFFERENCES = (
    "differences",
    "Differences between entrants against the same opponent (a − b in points: paired where they met the same "
    "layouts and seeds, else two means; the unpaired interval beside)",
)


def build_report(
    run_dirs: list[str | Path],
    out: Path,
    calibration: Path | None = None,
    with_replays: bool = True,
    mix_suites: bool = False,
    verify: bool = True,
) -> dict:
    found = find(run_dirs, calibration, mix_suites, verify)  # metrics computes; the rest only formats
    out.mkdir(parents=True, exist_ok=True)
    compares = comparison.answers(found.runs)
    sections = [  # the report's one list of sections: its files, its contents and its page
        *comparison.sections(compares, out),  # a comparison's answer first
        table("provenance", "Provenance: what each run is, from its manifests", provenance(found.runs)),
        table("summary", "Summary per red entrant (all scenarios and opponents)", found.summary),
        table("per_scenario", "Per red entrant and scenario", found.per_scenario),
        table("per_team", "Per entrant, whichever side it played (own points vs the opponent's)", found.per_team),
        table("pairings", "Per pairing (heatmap values)", found.pairs),
        table("groups", "Groups (adaptation: same/different opponent; self-play: after k episodes)", found.grouped),
        table(*DIFFERENCES, found.differences),  # two entrants against one opponent (paired where the worlds match)
        table(
            "side_symmetry",
            "Side symmetry: each team's points as red and as blue (✓: no side effect at 95 %)",
            found.symmetry,
        ),
        table(
            "fidelity",
            "Fidelity: built-in opponents against do_nothing beside upstream's reference (✓: within ±25 %) "
            "and the suite's own (vs_suite)",
            found.fidelity,
        ),
        table("claims", "Fidelity: the paper's Benchmark Analysis claims on this round robin", found.claims),
        *([table(unseen.NAME, unseen.TITLE, found.arenas)] if len(found.arenas) else []),  # generated layouts only
        *scenario_figures(found, out),
        *series_figures(found, out),
        table("learning_curve", "Points difference per episode index", found.curve),
        table("calibration", "σ_blue used for the sabotage metric", found.calibration),
        table("lagged", "Played under lag (spoiled: in no score; see docs/performance.md)", found.lag),
        table("faults", "Failures: ours (the harness) apart from the teams' own", found.faults),
        table("skipped", "Skipped", found.skipped),
    ]
    for s in sections:  # mixed suite versions, a bundle not verified: every table says so (its .md file too)
        s.title += found.title
    notes = [a.line() for _, a in compares] + report_notes(found)
    files: list[Path] = []
    if with_replays:
        replay_rows, files = replays.write_all(found.runs.series, out)
        recorded = sum(1 for r in replay_rows if r["replay"])
        notes.append(f"replays: {recorded} of {len(replay_rows)} episode(s) have a replay page (linked below)")
        html_rows = replays.table_html(replay_rows)
        sections.append(
            Section("Replays (one page per episode, opens offline)", "html", html_rows, empty=not replay_rows)
        )
    files += [f for s in sections for f in s.files(out)]
    shown = [(s.title, s.kind, s.content) for s in sections if not s.empty]
    page = out / "report.html"
    page.write_text(html.page("PillagerBench report", found.runs.runs, notes, shown, toc=True))
    files.append(page)
    lag = found.lag
    lagged = [(str(r[Col.SERIES]), int(r[Col.EPISODE]), str(r[Col.LAG_REASON])) for _, r in lag.iterrows()]
    runs = found.runs
    return {
        "files": files,
        "notes": notes,
        "skipped": runs.skipped,
        "lagged": lagged,
        "episodes": len(runs.episodes),
        "out": out,
    }


def report_notes(found: Findings) -> list[str]:
    """The notes above the report's tables, in their order."""
    runs = found.runs
    return [
        *found.mixed_notes,
        f"{len(runs.episodes)} episode(s) used (a team row's `episodes`, beside its `planned`), {len(runs.spoiled)} spoiled "
        f"on our side and in no score (the Failures table lists them), {len(runs.skipped)} item(s) skipped; Dash & Dine points ×0.1; "
        "± is the 95 % confidence interval",
        *found.calibration_notes,
        *more_notes(found),
        *found.fault_notes,
        *[
            f"read from the results bundle {b}{'' if b in runs.unverified else ', its checks passed'}"
            for b in runs.bundles
        ],
        *lag_notes(found.lag, found.one_order),
        *unseen.unseen_notes(found.main),
    ]


def scenario_figures(found: Findings, out: Path) -> list[Section]:
    """Per scenario: heatmaps, every team from its own side, points over time; each caption says
    what it shows and how many episodes stand behind it."""
    main, pairs, per_team, view = found.main, found.pairs, found.per_team, found.view
    sections = []
    for sc in scenario_order(found.runs.episodes):
        n = int((main[Col.SCENARIO] == sc).sum())
        n_pairs = int(((pairs["scenario"] == sc) & (pairs["blue"] != ALL)).sum())
        title = plots._title(sc)
        sections += [
            figure(
                f"Heatmaps: {title}",
                plots.heatmaps(pairs, sc, out / f"heatmaps_{sc}.png"),
                f"P, S, W and D of each red team (rows) against each opponent (columns) and over all, "
                f"mean ± 95 % CI: {n} episode(s) in {n_pairs} pairing(s).",
                n,
            ),
            figure(
                f"Per team: {title}",
                plots.teams(view, per_team, sc, out / f"teams_{sc}.png"),
                f"Every team from its own side, whichever side it played: P, S, D, W and its points over "
                f"time: {n} episode(s), each counted once for each of its two teams.",
                n,
            ),
            figure(
                f"Points over time: {title}",
                plots.timeline(main, sc, out / f"timeline_{sc}.png"),
                f"Mean points of each red team (solid) and of its opponents on the blue side (dashed) at each "
                f"second of the episode (95 % CI bands): {n} episode(s).",
                n,
            ),
        ]
    return sections


def series_figures(found: Findings, out: Path) -> list[Section]:
    """The figures over the episodes of a series: D per episode index, per group, self-play."""
    df, main, grouped, curve = found.runs.episodes, found.main, found.grouped, found.curve
    n_groups = int(grouped.loc[grouped["scenario"] != ALL, "episodes"].sum()) if len(grouped) else 0
    same = df[(df[Col.RED] == df[Col.BLUE]) & (df[Col.RED_TEAM] != "do_nothing")] if len(df) else df
    return [
        figure(
            "Points difference per episode",
            plots.learning_curve(curve, out / "learning_curve.png"),
            f"D (red − blue) by episode index within a series, mean ± 95 % CI: {len(main)} episode(s).",
            len(main),
        ),
        figure(
            "Groups",
            plots.groups(grouped, out / "groups.png"),
            f"D per evaluation group (adaptation, self-play after k episodes): {n_groups} episode(s).",
            n_groups,
        ),
        figure(
            "Self-play series",
            plots.series_scores(df, out / "series_scores.png"),
            f"Red and blue points per episode of the longest series of a team against itself: {len(same)} episode(s).",
            len(same),
        ),
    ]


def more_notes(found: Findings) -> list[str]:
    """Notes a reader needs to weigh the numbers: S without σ, n = 1, teams with problems, the
    fidelity checks, each run's scoring and protocol."""
    df, sigma, pairs, notes = found.runs.episodes, found.sigma, found.pairs, []
    bare = sorted(set(df[Col.SCENARIO]) - {sc for sc, _ in sigma}) if len(df) else []
    if bare:
        notes.append(f"no σ_blue for {', '.join(bare)} (pillagerbench calibrate): S is left empty there")
    one = pairs[(pairs["blue"] != ALL) & (pairs["episodes"] == 1)]
    if len(one):
        notes.append(
            f"n = 1: {len(one)} of {int((pairs['blue'] != ALL).sum())} pairing(s) rest on a single episode; "
            "their values have no confidence interval (marked “n = 1”)"
        )
    problems = [(r, side) for r in df.itertuples() for side in (r.problems or {})] if Col.PROBLEMS in df else []
    if problems:
        r, side = problems[-1]
        notes.append(
            f"{len(problems)} team-episode(s) with problems (model or team server not answering ...), e.g. "
            f"{r.series} episode {r.episode} ({side} {getattr(r, side)}): {r.problems[side][-1]}"
        )
    return notes + found.fidelity_notes + modes(df)


def lag_notes(lag: pd.DataFrame, one_order: list[str]) -> list[str]:
    notes = []
    if len(lag):
        notes.append(
            f"{len(lag)} episode(s) played under lag (spoiled: in no score; use a lower parallel=), e.g. "
            f"{lag.iloc[-1][Col.SERIES]} episode {lag.iloc[-1][Col.EPISODE]}: {lag.iloc[-1][Col.LAG_REASON]}"
        )
    if one_order:
        notes.append(f"side symmetry: {len(one_order)} note(s), e.g. {one_order[0]} (pillagerbench symmetry lists all)")
    return notes


def modes(df) -> list[str]:
    """One line per run: its scoring and the LLM teams' protocol (docs/fidelity.md)."""
    if not len(df):
        return []
    out = []
    for run, g in df.groupby(Col.RUN, sort=False):
        scoring = ", ".join(dict.fromkeys(g[Col.SCORING]))
        protocol = ", ".join(dict.fromkeys(g[Col.TEAM_PROTOCOL]))
        out.append(f"{run}: scoring {scoring}; LLM teams' protocol {protocol}")
    return out


def main(argv: list[str]) -> int:
    p = Parser(prog="pillagerbench report", description=__doc__.split("\n\n")[0])
    p.add_argument("runs", nargs="+", help="run directories (experiments or plain runs) or results bundles")
    p.add_argument(
        "--out", default=None, help="output directory (default: FIRST_RUN/report; beside a bundle: BUNDLE_report)"
    )
    p.add_argument(
        "--calibration",
        default=None,
        help="a calibration.json (pillagerbench calibrate), or `reference`: upstream's reference scores",
    )
    p.add_argument("--no-replays", action="store_true", help="do not write the episodes' replay pages")
    reader_switches(p)
    a = p.parse_args(argv)
    out = Path(a.out) if a.out else beside(Path(a.runs[0]), "report")
    try:
        calibration = Path(a.calibration) if a.calibration else None
        result = build_report(a.runs, out, calibration, not a.no_replays, a.mix_suites, not a.no_verify)
    except ReportError as exc:
        print(f"pillagerbench report: {exc}", file=sys.stderr)
        return 2
    for note in result["notes"]:
        print(note)
    for series, episode, why in result["lagged"]:
        print(f"lagged {series} episode {episode}: {why}")
    for where, why in result["skipped"]:
        print(f"skipped {where}: {why}")
    print(f"report: {out / 'report.html'} ({len(result['files'])} files)")
    return 0
