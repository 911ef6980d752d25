"""`pillagerbench report RUN_DIR... [--out DIR] [--calibration FILE|reference]`: the paper's tables and
figures from run directories (experiments or plain runs), as Markdown, CSV, PNG and one HTML page.

Dash & Dine scores are scaled ×0.1 as in the paper. σ_blue (for S) comes from --calibration (`reference`: upstream's reference scores), else
from calibration.json files stored in the runs, else from do_nothing-red episodes among the runs;
where none exists, S is left empty. Skipped episodes are listed with the reason in skipped.md and
on the page; runs of different scenario versions are refused.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from pillagerbench.metrics import calibration as calib
from pillagerbench.metrics.load import ReportError, load_runs
from pillagerbench.metrics.symmetry import side_symmetry
from pillagerbench.report import html, plots, replays, tables
from pillagerbench.report.fidelity import fidelity_sections


def build_report(
    run_dirs: list[str | Path], out: Path, calibration: Path | None = None, with_replays: bool = True
) -> dict:
    runs = load_runs(run_dirs)
    origin: dict = {}
    sigma, notes = calib.resolve(runs, calibration, origin)
    if not sigma:
        notes.append("no σ_blue for these runs (pillagerbench calibrate): S is left empty")
    df = runs.episodes
    out.mkdir(parents=True, exist_ok=True)
    main = tables.main_episodes(df)
    symmetry, one_order = side_symmetry(main)
    fidelity, claims, fidelity_notes = fidelity_sections(runs, sigma, origin)
    t = {
        "summary": (tables.summary(main, sigma, runs.ledger), "Summary per red team (all scenarios and opponents)"),
        "per_scenario": (tables.summary(main, sigma, runs.ledger, by_scenario=True), "Per red team and scenario"),
        "pairings": (tables.pairings(main, sigma), "Per pairing (heatmap values)"),
        "per_team": (tables.per_team(main, sigma), "Per team, whichever side it played (own points vs the opponent's)"),
        "groups": (
            tables.groups(df, sigma),
            "Groups (adaptation: same/different opponent; self-play: after k episodes)",
        ),
        "learning_curve": (tables.learning_curve(main), "Points difference per episode index"),
        "side_symmetry": (symmetry, "Side symmetry: each team's points as red and as blue (✓: no side effect at 95 %)"),
        "fidelity": (
            fidelity,
            "Fidelity: built-in opponents against do_nothing beside upstream's reference (✓: within ±25 %)",
        ),
        "claims": (claims, "Fidelity: the paper's Benchmark Analysis claims on this round robin"),
        "calibration": (tables.calibration(sigma), "σ_blue used for the sabotage metric"),
        "lagged": (tables.lagged(df), "Played under lag (used; scores may be low: see docs/performance.md)"),
        "skipped": (tables.skipped(runs.skipped), "Skipped"),
    }
    files = []
    for name, (frame, title) in t.items():
        files += tables.write(frame, out, name, title)
    scenarios = tables.scenario_order(df) if len(df) else []
    view = tables.team_view(main)
    figures = []  # (heading, path, caption: what it shows and how many episodes stand behind it)
    for sc in scenarios:
        n = int((main["scenario"] == sc).sum()) if len(main) else 0
        pairs = t["pairings"][0]
        n_pairs = int(((pairs["scenario"] == sc) & (pairs["blue"] != tables.ALL)).sum()) if len(pairs) else 0
        figures.append(
            (
                f"Heatmaps: {plots._title(sc)}",
                plots.heatmaps(pairs, sc, out / f"heatmaps_{sc}.png"),
                f"P, S, W and D of each red team (rows) against each opponent (columns) and over all, "
                f"mean ± 95 % CI: {n} episode(s) in {n_pairs} pairing(s).",
            )
        )
        figures.append(
            (
                f"Per team: {plots._title(sc)}",
                plots.teams(view, t["per_team"][0], sc, out / f"teams_{sc}.png"),
                f"Every team from its own side, whichever side it played: P, S, D, W and its points over "
                f"time: {n} episode(s), each counted once for each of its two teams.",
            )
        )
        figures.append(
            (
                f"Points over time: {plots._title(sc)}",
                plots.timeline(main, sc, out / f"timeline_{sc}.png"),
                f"Mean points of each red team at each second of the episode (95 % CI band): {n} episode(s).",
            )
        )
    grouped = t["groups"][0]
    n_main = len(main)
    n_groups = int(grouped.loc[grouped["scenario"] != tables.ALL, "episodes"].sum()) if len(grouped) else 0
    same = df[(df["red_team"] == df["blue_team"]) & (df["red_team"] != "do_nothing")] if len(df) else df
    figures.append(
        (
            "Points difference per episode",
            plots.learning_curve(t["learning_curve"][0], out / "learning_curve.png"),
            f"D (red − blue) by episode index within a series, mean ± 95 % CI: {n_main} episode(s).",
        )
    )
    figures.append(
        (
            "Groups",
            plots.groups(t["groups"][0], out / "groups.png"),
            f"D per evaluation group (adaptation, self-play after k episodes): {n_groups} episode(s).",
        )
    )
    figures.append(
        (
            "Self-play series",
            plots.series_scores(df, out / "series_scores.png"),
            f"Red and blue points per episode of the longest series of a team against itself: {len(same)} episode(s).",
        )
    )
    files += [p for _, p, _ in figures]
    notes.insert(
        0,
        f"{len(df)} episode(s) used, {len(runs.skipped)} item(s) skipped; Dash & Dine points ×0.1; "
        "± is the 95 % confidence interval",
    )
    without_model = (
        [(r, side) for r in df.itertuples() for side in (getattr(r, "problems", None) or {})]
        if len(df) and "problems" in df
        else []
    )
    if without_model:
        r, side = without_model[-1]
        notes.append(
            f"{len(without_model)} team-episode(s) with problems (model or team server not answering ...), e.g. "
            f"{r.series} episode {r.episode} ({side} {getattr(r, side)}): {r.problems[side][-1]}"
        )
    notes += fidelity_notes
    notes += modes(df)
    lag = t["lagged"][0]
    if len(lag):
        notes.append(
            f"{len(lag)} episode(s) played under lag (scores may be low; re-run them with a lower parallel=), e.g. "
            f"{lag.iloc[-1]['series']} episode {lag.iloc[-1]['episode']}: {lag.iloc[-1]['lag_reason']}"
        )
    if one_order:
        notes.append(f"side symmetry: {len(one_order)} note(s), e.g. {one_order[0]} (pillagerbench symmetry lists all)")
    sections = [
        (t[k][1], "table", t[k][0])
        for k in ("summary", "per_scenario", "per_team", "pairings", "groups", "side_symmetry")
    ]
    sections += [(t[k][1], "table", t[k][0]) for k in ("fidelity", "claims") if len(t[k][0])]
    sections += [(title, "image", (path, caption)) for title, path, caption in figures]
    sections += [(t[k][1], "table", t[k][0]) for k in ("learning_curve", "calibration", "lagged", "skipped")]
    if with_replays:
        replay_rows, pages = replays.write_all(runs.series, out)
        files += pages
        recorded = sum(1 for r in replay_rows if r["replay"])
        notes.append(f"replays: {recorded} of {len(replay_rows)} episode(s) have a replay page (linked below)")
        sections.append(("Replays (one page per episode, opens offline)", "html", replays.table_html(replay_rows)))
    page = out / "report.html"
    page.write_text(html.page("PillagerBench report", runs.runs, notes, sections))
    files.append(page)
    lagged = [(str(r["series"]), int(r["episode"]), str(r["lag_reason"])) for _, r in lag.iterrows()]
    return {"files": files, "notes": notes, "skipped": runs.skipped, "lagged": lagged, "episodes": len(df), "out": out}


def modes(df) -> list[str]:
    """One line per run: its scoring and the LLM teams' protocol (docs/fidelity.md)."""
    if not len(df):
        return []
    out = []
    for run, g in df.groupby("run", sort=False):
        scoring = ", ".join(dict.fromkeys(g["scoring"]))
        protocol = ", ".join(dict.fromkeys(g["team_protocol"]))
        out.append(f"{run}: scoring {scoring}; LLM teams' protocol {protocol}")
    return out


def main(argv: list[str]) -> int:
    p = argparse.ArgumentParser(prog="pillagerbench report", description=__doc__.split("\n\n")[0])
    p.add_argument("runs", nargs="+", help="run directories (experiments or plain runs)")
    p.add_argument("--out", default=None, help="output directory (default: FIRST_RUN/report)")
    p.add_argument(
        "--calibration",
        default=None,
        help="a calibration.json (pillagerbench calibrate), or `reference`: upstream's reference scores",
    )
    p.add_argument("--no-replays", action="store_true", help="do not write each episode's replay.html")
    a = p.parse_args(argv)
    out = Path(a.out) if a.out else Path(a.runs[0]) / "report"
    try:
        result = build_report(a.runs, out, Path(a.calibration) if a.calibration else None, not a.no_replays)
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
