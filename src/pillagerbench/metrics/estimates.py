"""The report's tables of estimates, computed: metrics hands them to the report, which only formats
them (report/tables.py). A "team" here is an entrant (metrics/entrants.py): `red` and `blue` are the
entrants' labels, and σ_blue is keyed by the opponent's entrant (a built-in team's is its name). Each
row's P, S, D, W is an `EntrantEstimate` (metrics/estimate.py).

- summary:       per red team (row label) over every scenario and opponent: P S D W, T_resp N_out R_tps, I
                 (the paper's main table, model ablation and module ablation); `episodes` used of `planned`
                 (an episode spoiled on our side is in no score: metrics/runs.py)
- per_scenario:  the same per red team and scenario
- pairings:      per scenario, red team and opponent, plus "all": P S D W (the heatmaps' numbers)
- per_team:      per team, whichever side it played (team_estimates)
- groups:        per red team, scenario (and "all") and group: adaptation same/different, self-play
                 evaluation "after k" (paper's adaptation table and self-play figure)
- learning_curve: D per episode index (experience) per red team (paper's D-per-episode figure)
- calibration:   σ_blue used per scenario and opponent
- lagged:        episodes played under lag (pillagerbench/host/machine.py) and why: spoiled, in no score
- skipped:       what was left out and why
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from pillagerbench.config.sides import SIDES, other_side
from pillagerbench.metrics.calibration import opponent_groups
from pillagerbench.metrics.columns import Col
from pillagerbench.metrics.estimate import COLUMNS, EntrantEstimate, Group
from pillagerbench.metrics.formulas import iterations, llm_metrics, mean_ci

ALL = "all"


def scenario_order(df: pd.DataFrame) -> list[str]:
    known = ["mushroom_war", "dash_and_dine"]
    present = list(dict.fromkeys(df[Col.SCENARIO])) if len(df) else []
    return [s for s in known if s in present] + [s for s in present if s not in known]


def opponent_order(df: pd.DataFrame, scenario: str | None = None) -> list[str]:
    from pillagerbench.experiments.spec import builtin_teams

    sub = df if scenario is None else df[df[Col.SCENARIO] == scenario]
    present = list(dict.fromkeys(sub[Col.BLUE])) if len(sub) else []
    canon: list[str] = []
    for sc in [scenario] if scenario else scenario_order(df):
        canon += [t for t in builtin_teams(sc) if t not in canon]
    return [t for t in canon if t in present] + [t for t in present if t not in canon]


def red_order(df: pd.DataFrame) -> list[str]:
    return list(dict.fromkeys(df[Col.RED])) if len(df) else []


def main_episodes(df: pd.DataFrame) -> pd.DataFrame:
    """Episodes of ordinary series (not evaluation groups such as adaptation's same/different)."""
    if not len(df):
        return df
    return df[df[Col.GROUP].isna() | (df[Col.GROUP] == "training")]


def pairings(df: pd.DataFrame, sigma: dict) -> pd.DataFrame:
    rows = []
    for scenario in scenario_order(df):
        sd = df[df[Col.SCENARIO] == scenario]
        for red in red_order(sd):
            rd = sd[sd[Col.RED] == red]
            for blue in opponent_order(rd, scenario):
                g = rd[rd[Col.BLUE] == blue]
                e = EntrantEstimate.against(g[Col.RED_SCORE], g[Col.BLUE_SCORE], sigma.get((scenario, blue)))
                rows.append({"scenario": scenario, "red": red, "blue": blue, **e.columns()})
            rows.append(
                {
                    "scenario": scenario,
                    "red": red,
                    "blue": ALL,
                    **EntrantEstimate.over(opponent_groups(rd, sigma)).columns(),
                }
            )
    return pd.DataFrame(rows, columns=["scenario", "red", "blue", "episodes", *COLUMNS])


def planned(series: list, *frames: pd.DataFrame) -> dict[tuple[str, str], int]:
    """Episodes the ordinary series (not evaluation groups) planned, per (red entrant, scenario): a
    series' red entrant is the name its episodes (`frames`: used, spoiled) show, else its config's."""
    named: dict[tuple[str, str], str] = {}
    for frame in frames:
        if len(frame):
            named.update({(r, s): red for r, s, red in zip(frame[Col.RUN], frame[Col.SERIES], frame[Col.RED])})
    out: dict[tuple[str, str], int] = {}
    for s in series:
        if s.group is None or s.group == "training":
            red = named.get((str(s.run), s.id)) or s.entrants["red"].label
            out[(red, s.scenario)] = out.get((red, s.scenario), 0) + int(s.episodes)
    return out


def summary(
    df: pd.DataFrame, sigma: dict, ledger: list[dict], by_scenario: bool = False, plan: dict | None = None
) -> pd.DataFrame:
    """`plan`: episodes planned per (red, scenario) (`planned`); a red row with none used still shows
    (0 of its planned episodes: every one spoiled on our side)."""
    rows = []
    plan = plan or {}
    keys: list[tuple[str, str | None]] = [(r, None) for r in red_order(df)]
    if by_scenario:
        keys = [(r, sc) for sc in scenario_order(df) for r in red_order(df[df[Col.SCENARIO] == sc])]
    keys = list(dict.fromkeys(keys + [(r, sc if by_scenario else None) for r, sc in plan]))
    for red, scenario in keys:
        wanted = sum(n for (r, sc), n in plan.items() if r == red and scenario in (None, sc))
        head = {"red": red, **({"scenario": scenario} if by_scenario else {}), "planned": wanted or np.nan}
        rd = df[(df[Col.RED] == red) & ((df[Col.SCENARIO] == scenario) if scenario else True)] if len(df) else df
        rows.append({**head, **(_summary_row(rd, red, scenario, sigma, ledger) if len(rd) else {"episodes": 0})})
    cols = (
        ["red"]
        + (["scenario"] if by_scenario else [])
        + ["episodes", "planned"]
        + COLUMNS
        + ["T_resp", "N_out", "R_tps", "llm_calls", "cost", "cost_per_win", "I", "I_ci"]
    )
    return pd.DataFrame(rows, columns=cols)


def _summary_row(rd: pd.DataFrame, red: str, scenario: str | None, sigma: dict, ledger: list[dict]) -> dict:
    """P S D W over the opponents, the LLM metrics and I of one red row's used episodes."""
    calls = [c for c in ledger if c.get("label") == red and (scenario is None or c.get("scenario") == scenario)]
    llm = llm_metrics(calls)
    it = iterations([[x] for x in rd[Col.ITERATIONS] if not math.isnan(x)])
    paid = cost_of(calls, wins=int((rd[Col.RED_SCORE] > rd[Col.BLUE_SCORE]).sum()))
    return {
        **EntrantEstimate.over(opponent_groups(rd, sigma)).columns(),
        "T_resp": llm["T_resp"],
        "N_out": llm["N_out"],
        "R_tps": llm["R_tps"],
        "llm_calls": llm["calls"],
        **paid,
        "I": it.mean,
        "I_ci": it.ci,
    }


def cost_of(calls: list[dict], wins: int) -> dict[str, str]:
    """What the team's calls cost (ledger: "$0.0123", "≥ $… (n calls unpriced)", "unknown (…)") and per
    episode won ("–" without calls or wins; "unknown" when some call is unpriced)."""
    from pillagerbench.llm.ledger import summarize  # the llm package loads openai: only when asked
    from pillagerbench.llm.prices import format_cost

    if not calls:
        return {"cost": "–", "cost_per_win": "–"}
    stats = summarize(calls)
    if not wins:
        per_win = "– (no win)"
    elif stats.unpriced:
        per_win = "unknown"
    else:
        per_win = format_cost(stats.cost_usd / wins, 0)
    return {"cost": stats.cost_text(), "cost_per_win": per_win}


def team_view(df: pd.DataFrame) -> pd.DataFrame:
    """Every episode twice, once from each side: scenario, team (label), opponent, side played,
    own and opponent's final points and own points over time (`t`, `own_t`)."""
    cols = ["scenario", "team", "team_name", "opponent", "opponent_team", "side", "own", "opp", "t", "own_t"]
    if not len(df):
        return pd.DataFrame(columns=cols)
    parts = []
    for side, other in ((s, other_side(s)) for s in SIDES):
        parts.append(
            pd.DataFrame(
                {
                    "scenario": df[Col.SCENARIO].to_numpy(),
                    "team": df[Col.name(side)].to_numpy(),
                    "team_name": df[Col.team(side)].to_numpy(),
                    "opponent": df[Col.name(other)].to_numpy(),
                    "opponent_team": df[Col.team(other)].to_numpy(),
                    "side": side,
                    "own": df[Col.score(side)].to_numpy(),
                    "opp": df[Col.score(other)].to_numpy(),
                    "t": list(df[Col.T]),
                    "own_t": list(df[Col.over_time(side)]),
                }
            )
        )
    return pd.concat(parts, ignore_index=True)[cols]


def team_order(view: pd.DataFrame) -> list[str]:
    return list(dict.fromkeys(view["team"])) if len(view) else []


def team_estimates(df: pd.DataFrame, sigma: dict) -> dict[tuple[str, str], tuple[EntrantEstimate, pd.DataFrame]]:
    """(scenario, team) -> its P, S, D, W from its own side of the board, whichever side it played (a
    calibration run shows the opponents' points, not only do_nothing's zeros), and its episodes as
    team_view shows them. S uses the opponent's σ (its mean points against do_nothing)."""
    view = team_view(df)
    out = {}
    for scenario in scenario_order(df):
        sd = view[view["scenario"] == scenario]
        for team in team_order(sd):
            td = sd[sd["team"] == team]
            groups_: list[Group] = [
                (g["own"].to_numpy(), g["opp"].to_numpy(), s.mean if s else None, s)
                for opponent, g in td.groupby("opponent", sort=False)
                for s in [sigma.get((scenario, str(opponent)))]
            ]
            out[(scenario, team)] = EntrantEstimate.over(groups_), td
    return out


def per_team(df: pd.DataFrame, sigma: dict) -> pd.DataFrame:
    """team_estimates as the report's table, with how often each team played each side."""
    rows = [
        {
            "scenario": scenario,
            "team": team,
            "as_red": int((td["side"] == "red").sum()),
            "as_blue": int((td["side"] == "blue").sum()),
            **e.columns(),
        }
        for (scenario, team), (e, td) in team_estimates(df, sigma).items()
    ]
    return pd.DataFrame(rows, columns=["scenario", "team", "episodes", "as_red", "as_blue", *COLUMNS])


def groups(df: pd.DataFrame, sigma: dict) -> pd.DataFrame:
    gd = df[df[Col.GROUP].notna() & (df[Col.GROUP] != "training")] if len(df) else df
    rows = []
    if len(gd):
        order = sorted(dict.fromkeys(gd[Col.GROUP]), key=lambda g: (_sort_x(_group_x(gd, g)), g))
        for red in red_order(gd):
            for scenario in scenario_order(gd) + [ALL]:
                sd = gd[(gd[Col.RED] == red) & ((gd[Col.SCENARIO] == scenario) if scenario != ALL else True)]
                for group in order:
                    g = sd[sd[Col.GROUP] == group]
                    if len(g):
                        rows.append(
                            {
                                "red": red,
                                "scenario": scenario,
                                "group": group,
                                "group_x": _group_x(gd, group),
                                **EntrantEstimate.over(opponent_groups(g, sigma)).columns(),
                            }
                        )
    return pd.DataFrame(rows, columns=["red", "scenario", "group", "group_x", "episodes", *COLUMNS])


def _group_x(df: pd.DataFrame, group: str) -> float:
    x = df.loc[df[Col.GROUP] == group, Col.GROUP_X].dropna()
    return float(x.iloc[0]) if len(x) else math.nan


def _sort_x(x: float) -> float:
    return math.inf if math.isnan(x) else x


def learning_curve(df: pd.DataFrame) -> pd.DataFrame:
    rows = []
    for red in red_order(df):
        rd = df[df[Col.RED] == red]
        for index in sorted(rd[Col.INDEX].unique()):
            g = rd[rd[Col.INDEX] == index]
            d = mean_ci(g[Col.RED_SCORE] - g[Col.BLUE_SCORE])
            rows.append({"red": red, "episode": int(index), "episodes": d.n, "D": d.mean, "D_ci": d.ci})
    return pd.DataFrame(rows, columns=["red", "episode", "episodes", "D", "D_ci"])


def calibration(sigma: dict) -> pd.DataFrame:
    rows = [
        {"scenario": sc, "opponent": team, "sigma_blue": e.mean, "sigma_blue_ci": e.ci, "episodes": e.n}
        for (sc, team), e in sigma.items()
    ]
    return pd.DataFrame(rows, columns=["scenario", "opponent", "sigma_blue", "sigma_blue_ci", "episodes"])


def lagged(df: pd.DataFrame) -> pd.DataFrame:
    """Episodes played under lag (a threshold of pillagerbench/host/machine.py crossed; give the spoiled
    rows, metrics/runs.py): in no score, listed so a reader sees why and can lower `parallel`."""
    cols = [Col.SERIES, Col.EPISODE, Col.SERVER_TPS, Col.LAG_REASON]
    if not len(df) or Col.LAGGED not in df:
        return pd.DataFrame(columns=cols)
    return df.loc[df[Col.LAGGED].astype(bool), cols].reset_index(drop=True)


def skipped(items: list[tuple[str, str]]) -> pd.DataFrame:
    return pd.DataFrame([{"where": w, "why": y} for w, y in items], columns=["where", "why"])
