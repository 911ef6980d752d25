"""`pillagerbench league LEAGUE_DIR board`: leaderboard.md, .csv and .html in the league directory,
rebuilt only from the rounds' episodes.jsonl (and their ledgers), so the same files give the same board.

The main table (also the CSV): rank by overall rating (equal ratings share a rank: 1, 1, 3),
entrant (its name in league.yaml), team, the entrant's label and id as its episodes recorded them
(team, model per role and play options: teams/entrant.py), the Bradley–Terry rating with its bootstrap interval and the
pool's maximal lottery (arena_view.py), rating ± interval (at the league's confidence), conservative rating (mu − 3σ),
episodes; per scenario its rating and the entrant's P, S, W over all its episodes on either side
(S against each opponent with that opponent's mean score against do_nothing in the league as σ,
where it has played do_nothing);
LLM tokens, cost per episode and per win when the ledgers have any. Then a head-to-head matrix per scenario,
and rating against dollars (leaderboard_cost.png) when a cost is known.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd

from pillagerbench.config.sides import SIDES
from pillagerbench.league import results, splits
from pillagerbench.league.arena_view import BOOTSTRAP_ROUNDS, COLUMNS, arena_columns, cost_plot
from pillagerbench.league.ratings import ANCHOR, Rating, ranked, ranks
from pillagerbench.league.spec import League
from pillagerbench.league.standings import boards, overall
from pillagerbench.metrics.columns import Col
from pillagerbench.metrics.formulas import Estimate, mean_ci, mean_of_estimates, sabotage, win_rate
from pillagerbench.metrics.runs import mixed_notes, mixed_title
from pillagerbench.report.html import page
from pillagerbench.report.tables import to_markdown

FILES = ("leaderboard.md", "leaderboard.csv", "leaderboard.html")
COST_PLOT = "leaderboard_cost.png"  # written when an entrant's LLM cost is known


def _episodes(runs: results.Runs) -> pd.DataFrame:
    return runs.episodes if len(runs.episodes) else pd.DataFrame(columns=["scenario", *NAMES, *SCORES])


SCORES = ("red_score", "blue_score")
NAMES = ("red_name", "blue_name", "red_entrant", "blue_entrant", "red_entrant_id", "blue_entrant_id")


def _sides(df: pd.DataFrame, name: str) -> pd.DataFrame:
    """The entrant's episodes as (opponent, own, opp) rows, whichever side it played."""
    red, blue = df[df["red_name"] == name], df[df["blue_name"] == name]
    return pd.DataFrame(
        {
            "opponent": list(red["blue_name"]) + list(blue["red_name"]),
            "own": list(red["red_score"]) + list(blue["blue_score"]),
            "opp": list(red["blue_score"]) + list(blue["red_score"]),
        }
    )


def _recorded(df: pd.DataFrame, name: str) -> dict[str, str]:
    """The entrant label and id its episodes recorded (teams/entrant.py), "" before it played."""
    seen: dict[str, str] = {}
    for side in SIDES:
        mine = df[df[Col.series_name(side)] == name]
        seen |= dict(zip(mine[Col.entrant_id(side)], mine[Col.entrant(side)]))
    return {"label": ", ".join(dict.fromkeys(seen.values())), "id": ", ".join(seen)}


def _sabotage(df: pd.DataFrame, mine: pd.DataFrame) -> Estimate:
    per = []
    for opponent, rows in mine.groupby("opponent"):
        vs_anchor = _sides(df, str(opponent))
        sigma = vs_anchor[vs_anchor["opponent"] == ANCHOR]["own"]
        if len(sigma):
            per.append(sabotage(list(rows["opp"]), float(np.mean(sigma))))
    return mean_of_estimates(per)


def _cells(prefix: str, estimates: dict[str, Estimate]) -> dict:
    out: dict = {}
    for key, e in estimates.items():
        out[f"{prefix}{key}"], out[f"{prefix}{key}_ci"] = e.mean, e.ci
    return out


def leaderboard(league: League, runs: results.Runs) -> pd.DataFrame:
    outs = results.outcomes(runs)
    per, total = boards(league, outs), overall(league, outs)
    df, spend = _episodes(runs), results.ledger(runs)
    z_conf = league.confidence
    rows, place = [], ranks(total)
    chosen = set(league.scenarios)
    arena = arena_columns([o for o in outs if o.scenario in chosen], [e.name for e in league.entrants], spend)
    for name in ranked(total):
        entrant = league.entrant(name)
        r: Rating = total[name]
        row = {
            "rank": place[name],
            "entrant": name,
            "team": entrant.team if entrant else "",
            **_recorded(df, name),
            **{k: arena[name][k] for k in COLUMNS[:5]},  # Bradley-Terry and the pool's view (arena_view.py)
            "rating": r.mu,
            "rating_ci": r.interval(z_conf),
            "conservative": r.conservative,
            "episodes": r.episodes,
        }
        for sc, board in per.items():
            if name not in board:
                continue
            mine = _sides(df[df["scenario"] == sc], name)
            row |= {f"{sc} rating": board[name].mu, f"{sc} rating_ci": board[name].interval(z_conf)}
            row |= _cells(
                f"{sc} ",
                {
                    "P": mean_ci(mine["own"]),
                    "S": _sabotage(df[df["scenario"] == sc], mine) if len(mine) else mean_ci([]),
                    "W": win_rate(mine["own"], mine["opp"]),
                },
            )
        calls = spend[spend["entrant"] == name]
        known = r.episodes and len(calls)
        row["LLM tokens/episode"] = calls["tokens"].sum() / r.episodes if known else math.nan
        priced = known and not calls["cost"].isna().any()  # a call without a price: the cost is unknown, not 0
        row["LLM cost/episode"] = calls["cost"].astype(float).sum() / r.episodes if priced else math.nan
        row["LLM cost/win"] = arena[name]["LLM cost/win"]
        rows.append(row)
    return pd.DataFrame(rows)


def head_to_head(league: League, runs: results.Runs, scenario: str) -> pd.DataFrame:
    """Row entrant's win rate against the column entrant (both sides pooled), with the episodes."""
    df = _episodes(runs)
    df = df[df["scenario"] == scenario]
    names = ranked(boards(league, results.outcomes(runs))[scenario])
    table = []
    for a in names:
        mine = _sides(df, a)
        row: dict = {"entrant": a}
        for b in names:
            games = mine[mine["opponent"] == b]
            row[b] = f"{win_rate(games['own'], games['opp']).mean:.2f} ({len(games)})" if len(games) else ""
        table.append(row)
    return pd.DataFrame(table, columns=["entrant", *names])


def write_board(league_dir: Path, league: League) -> list[Path]:
    runs, on = splits.on_split(results.load(league_dir, league.mix_suites, not league.no_verify), league.split)
    main = leaderboard(league, runs).assign(split=league.split)  # the layouts its ratings are from
    h2h = {sc: head_to_head(league, runs, sc) for sc in league.scenarios}
    notes = [
        f"{len(runs.episodes)} episodes in {len(runs.runs)} rounds; BT rating: Bradley–Terry on the Elo scale with its "
        f"bootstrap 95 % interval ({BOOTSTRAP_ROUNDS} resamples of the episodes); lottery share and Nash margin: the "
        "pool's maximal lottery and each entrant's expected margin against it (0 for those it holds); rating ± its "
        f"{league.confidence:.0%} interval (openskill Plackett–Luce, the order and the scheduler's), both with "
        "do_nothing = 0; conservative = mu − 3σ",
        f"{len(runs.skipped)} items skipped (unfinished or failed episodes)",
        *on,
        *mixed_notes(runs),
    ]
    unpriced = int(results.ledger(runs)["cost"].isna().sum())
    if unpriced:
        notes.append(f"LLM cost unknown (left blank) where {unpriced} calls had no price for their model (docs/llm.md)")
    out = Path(league_dir)
    main.to_csv(out / "leaderboard.csv", index=False)
    # mixed suites, unverified bundles, the split: every table says so
    mixed = mixed_title(runs) + splits.title(league.split)
    md = [f"# League {out.name}", "", *(f"- {n}" for n in notes), "", f"## Leaderboard{mixed}", "", to_markdown(main)]
    for sc, t in h2h.items():
        md += ["", f"## Head to head, {sc} (row's win rate against column, episodes){mixed}", "", to_markdown(t)]
    plot = cost_plot(main, out / COST_PLOT)
    if plot is not None:
        md += ["", f"## Rating against dollars{mixed}", "", f"![BT rating against LLM cost per episode]({COST_PLOT})"]
    (out / "leaderboard.md").write_text("\n".join(md) + "\n")
    sections = [(f"Leaderboard{mixed}", "table", main)] + [
        (f"Head to head, {sc} (row's win rate against column, episodes){mixed}", "table", t) for sc, t in h2h.items()
    ]
    if plot is not None:
        sections.append((f"Rating against dollars{mixed}", "image", plot))
    (out / "leaderboard.html").write_text(page(f"League {out.name}", runs.runs, notes, sections, runs_label="Rounds"))
    return [out / f for f in FILES]
