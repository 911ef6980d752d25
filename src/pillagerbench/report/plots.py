"""The report's figures (matplotlib, Agg backend, PNG), each with 95 % confidence intervals:

- heatmaps_<scenario>.png   P, S, W, D per red team (rows) and opponent (columns, plus "all")
- teams_<scenario>.png      each team's P, S, D, W and points over time, whichever side it played
- timeline_<scenario>.png   mean points over the episode per red team and of its opponents (blue), shaded CI bands
- learning_curve.png        D per episode index (experience) per red team, CI error bars
- groups.png                P/D per group (adaptation same/different, self-play "after k")
- series_scores.png         red and blue score per episode of long series where a team meets itself
- compare_<run>.png         a compare's log-likelihood ratio after each pair, between its bounds
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import cast

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from pillagerbench.config.sides import SIDES
from pillagerbench.metrics.columns import Col
from pillagerbench.metrics.estimates import ALL, opponent_order, red_order
from pillagerbench.metrics.formulas import t_critical

TITLES = {
    "P": "Points (red team)",
    "S": "Sabotage (red team)",
    "W": "Win rate (red team)",
    "D": "Points difference (red − blue)",
}
CMAPS = {"P": "viridis", "S": "viridis", "W": "coolwarm", "D": "coolwarm"}
SCENARIO_TITLES = {"mushroom_war": "Mushroom War", "dash_and_dine": "Dash & Dine"}


def _title(scenario: str) -> str:
    return SCENARIO_TITLES.get(scenario, scenario)


def _empty(path: Path, text: str) -> Path:
    fig, ax = plt.subplots(figsize=(6, 2))
    ax.axis("off")
    ax.text(0.5, 0.5, text, ha="center", va="center")
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def heatmap_size(n_rows: int, n_cols: int, label_len: int = 12) -> tuple[float, float]:
    """(width, height) in inches of one heatmap panel: cells of a fixed size, plus room for the row
    labels, the rotated column labels and the title, so 1 row or 12 stay legible."""
    cell_w, cell_h = 0.85, 0.5
    label_w = 0.2 + 0.075 * label_len
    return label_w + 1.2 + cell_w * max(n_cols, 2), 1.9 + cell_h * max(n_rows, 1.6)


def heatmaps(pairs: pd.DataFrame, scenario: str, path: Path) -> Path:
    sd = pairs[pairs["scenario"] == scenario]
    if not len(sd):
        return _empty(path, f"{_title(scenario)}: no episodes")
    rows = red_order(sd)
    cols = [*opponent_order(sd[sd["blue"] != ALL], scenario), ALL]
    w, h = heatmap_size(len(rows), len(cols), max(len(r) for r in rows))
    fig, grid_axes = plt.subplots(2, 2, figsize=(2 * w, 2 * h + 0.4), layout="constrained")
    axes = grid_axes.ravel()
    font = 7 if len(cols) > 6 else 8
    for ax, metric in zip(axes, ("P", "S", "W", "D")):
        grid = np.full((len(rows), len(cols)), np.nan)
        ci = np.full_like(grid, np.nan)
        for _, r in sd.iterrows():
            i, j = rows.index(r["red"]), cols.index(r["blue"])
            grid[i, j], ci[i, j] = r[metric], r[f"{metric}_ci"]
        masked = np.ma.masked_invalid(grid)
        kw: dict[str, float] = {"vmin": 0, "vmax": 1} if metric == "W" else {}
        if metric == "D" and np.isfinite(grid).any():
            lim = np.nanmax(np.abs(grid)) or 1.0
            kw = {"vmin": -lim, "vmax": lim}
        im = ax.imshow(masked, cmap=CMAPS[metric], aspect="auto", **kw)
        for i in range(len(rows)):
            for j in range(len(cols)):
                if np.isfinite(grid[i, j]):
                    text = f"{grid[i, j]:.2f}" + (f"\n±{ci[i, j]:.2f}" if np.isfinite(ci[i, j]) else "")
                    ax.text(
                        j,
                        i,
                        text,
                        ha="center",
                        va="center",
                        fontsize=font,
                        color="white" if metric in "PS" else "black",
                    )
                else:
                    ax.text(j, i, "–", ha="center", va="center", fontsize=font, color="grey")
        ax.set_xticks(range(len(cols)), cols, rotation=35, ha="right", fontsize=8)
        ax.set_yticks(range(len(rows)), rows, fontsize=8)
        ax.set_title(TITLES[metric], fontsize=10)
        ax.set_xlabel("blue team (opponent)", fontsize=8)
        ax.set_ylabel("red team", fontsize=8)
        if np.isfinite(grid).any():
            fig.colorbar(im, ax=ax, fraction=0.05, pad=0.02, shrink=0.9 if len(rows) > 2 else 1.0)
        else:  # no scale for a panel without values (S without any σ_blue)
            ax.set_title(f"{TITLES[metric]}: no values", fontsize=10)
    fig.suptitle(f"{_title(scenario)} (mean ± 95 % CI)")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def teams(view: pd.DataFrame, table: pd.DataFrame, scenario: str, path: Path) -> Path:
    """Each team from its own side, whichever side it played: P, S, D, W (bars with 95 % CI) and its
    mean points over time (shaded 95 % CI)."""
    sd = view[view["scenario"] == scenario] if len(view) else view
    td = table[table["scenario"] == scenario] if len(table) else table
    if not len(sd):
        return _empty(path, f"{_title(scenario)}: no episodes")
    names = list(td["team"])
    height = 1.4 + 0.38 * max(len(names), 2)
    fig = plt.figure(figsize=(17, max(3.6, height)), layout="constrained")
    sub = cast(np.ndarray, fig.subfigures(1, 2, width_ratios=[3, 1.3]))
    bars = sub[0].subplots(1, 4, sharey=True)
    y = np.arange(len(names))
    colours = [plt.get_cmap("tab10")(i % 10) for i in range(len(names))]
    for ax, metric in zip(bars, ("P", "S", "D", "W")):
        values, cis = td[metric].to_numpy(dtype=float), td[f"{metric}_ci"].to_numpy(dtype=float)
        ax.barh(y, np.nan_to_num(values), xerr=np.where(np.isfinite(cis), cis, 0), color=colours, capsize=3)
        for i, v in enumerate(values):
            ax.text(0, i, " –" if not np.isfinite(v) else "", va="center", fontsize=8, color="grey")
        ax.axvline(0, color="grey", lw=0.8)
        ax.set_title(
            {"P": "Points", "S": "Sabotage", "D": "Points difference (own − opp.)", "W": "Win rate"}[metric], fontsize=9
        )
        ax.tick_params(labelsize=8)
    bars[0].set_yticks(y, [f"{n} ({r}+{b})" for n, r, b in zip(names, td["as_red"], td["as_blue"])], fontsize=8)
    bars[0].invert_yaxis()
    bars[0].set_ylabel("team (episodes as red + as blue)", fontsize=8)
    ax = sub[1].subplots()
    for name, colour in zip(names, colours):
        g = sd[sd["team"] == name]
        n_t = min(len(t) for t in g["t"])
        t = np.asarray(g["t"].iloc[0][:n_t])
        ys = np.stack([np.asarray(v[:n_t]) for v in g["own_t"]])
        mean = ys.mean(axis=0)
        ax.plot(t, mean, color=colour, label=f"{name} (n={len(ys)})")
        if len(ys) > 1:
            half = t_critical(len(ys) - 1) * ys.std(axis=0, ddof=1) / math.sqrt(len(ys))
            ax.fill_between(t, mean - half, mean + half, color=colour, alpha=0.15)
    ax.set_xlabel("time (s)", fontsize=8)
    ax.set_ylabel("own points" + (" ×0.1" if scenario == "dash_and_dine" else ""), fontsize=8)
    ax.set_title("Points over time (either side)", fontsize=9)
    ax.legend(fontsize=7)
    fig.suptitle(f"{_title(scenario)}: every team from its own side (mean, 95 % CI)")
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def timeline_lines(df: pd.DataFrame, scenario: str) -> list[dict]:
    """What the timeline draws: for each red team, its own mean points over the episode and its
    opponents' (the blue side), each with the 95 % half-width (None for one episode)."""
    sd = df[df["scenario"] == scenario] if len(df) else df
    lines = []
    for red in red_order(sd):
        rd = sd[sd["red"] == red]
        n_t = min(len(t) for t in rd["t"])
        for side in SIDES:
            y = np.stack([v[:n_t] for v in rd[Col.over_time(side)]])
            half = t_critical(len(y) - 1) * y.std(axis=0, ddof=1) / math.sqrt(len(y)) if len(y) > 1 else None
            label = f"{red} (red, n={len(y)})" if side == "red" else f"{red}'s opponents (blue)"
            t = rd["t"].iloc[0][:n_t]
            lines.append({"red": red, "side": side, "label": label, "t": t, "mean": y.mean(0), "half": half})
    return lines


def timeline(df: pd.DataFrame, scenario: str, path: Path) -> Path:
    lines = timeline_lines(df, scenario)
    if not lines:
        return _empty(path, f"{_title(scenario)}: no episodes")
    fig, ax = plt.subplots(figsize=(7, 4))
    colours = {red: plt.get_cmap("tab10")(i % 10) for i, red in enumerate(dict.fromkeys(x["red"] for x in lines))}
    for x in lines:
        colour = colours[x["red"]]
        ax.plot(x["t"], x["mean"], color=colour, ls="-" if x["side"] == "red" else "--", label=x["label"])
        if x["half"] is not None:
            ax.fill_between(x["t"], x["mean"] - x["half"], x["mean"] + x["half"], color=colour, alpha=0.15)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("points" + (" ×0.1" if scenario == "dash_and_dine" else ""))
    ax.set_title(f"{_title(scenario)}: points over time, red (solid) and blue (dashed), 95 % CI")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def learning_curve(curve: pd.DataFrame, path: Path) -> Path:
    if not len(curve):
        return _empty(path, "no episodes")
    fig, ax = plt.subplots(figsize=(7, 4))
    for red in red_order(curve):
        c = curve[curve["red"] == red]
        ax.errorbar(c["episode"], c["D"], yerr=c["D_ci"].fillna(0), marker="^", capsize=3, label=red)
    ax.axhline(0, color="grey", lw=0.8)
    ax.set_xlabel("episode (consecutive, with the same team object)")
    ax.set_ylabel("D (red − blue)")
    ax.set_title("Points difference over episodes (95 % CI)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def groups(table: pd.DataFrame, path: Path) -> Path:
    if not len(table):
        return _empty(path, "no grouped series (adaptation or self-play evaluation)")
    scenarios = list(dict.fromkeys(table["scenario"]))
    fig, axes = plt.subplots(1, len(scenarios), figsize=(4.5 * len(scenarios), 4), squeeze=False)
    for ax, scenario in zip(axes[0], scenarios):
        sd = table[table["scenario"] == scenario]
        numeric = sd["group_x"].apply(lambda x: x is not None and not math.isnan(x)).all()
        for red in red_order(sd):
            r = sd[sd["red"] == red]
            x = r["group_x"] if numeric else np.arange(len(r))
            ax.errorbar(x, r["D"], yerr=r["D_ci"].fillna(0), marker="o", capsize=3, label=red)
            if not numeric:
                ax.set_xticks(np.arange(len(r)), r["group"])
        ax.axhline(0, color="grey", lw=0.8)
        ax.set_title(_title(scenario) if scenario != ALL else "all scenarios")
        ax.set_xlabel("episodes of experience" if numeric else "group")
        ax.set_ylabel("D (red − blue)")
        ax.legend(fontsize=8)
    fig.suptitle("Points difference by group (95 % CI)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def series_scores(df: pd.DataFrame, path: Path, max_series: int = 6) -> Path:
    """Red and blue points per episode of the longest series in which an entrant plays itself (self-play)."""
    if not len(df):
        return _empty(path, "no episodes")
    same = df[(df["red"] == df["blue"]) & (df["red_team"] != "do_nothing")]
    if not len(same):
        return _empty(path, "no self-play series")
    ids = list(same.groupby("series").size().sort_values(ascending=False).index[:max_series])
    fig, axes = plt.subplots(len(ids), 1, figsize=(7, 2.6 * len(ids)), squeeze=False)
    for ax, sid in zip(axes[:, 0], ids):
        s = same[same["series"] == sid].sort_values("episode")
        ax.plot(s["episode"], s["red_score"], "o-", color="tab:red", label="red")
        ax.plot(s["episode"], s["blue_score"], "s-", color="tab:blue", label="blue")
        ax.set_title(sid, fontsize=9)
        ax.set_xlabel("episode")
        ax.set_ylabel("points")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def sprt_path(llrs: list[float], lower: float, upper: float, title: str, path: Path) -> Path:
    """A sequential test's log-likelihood ratio after each pair, between its two bounds (a compare)."""
    fig, ax = plt.subplots(figsize=(7, 3.5))
    pairs = list(range(len(llrs) + 1))
    ax.plot(pairs, [0.0, *llrs], marker="o", color="#1f77b4", label="LLR after each pair")
    ax.axhline(upper, color="#2ca02c", ls="--", label=f"A better ({upper:+.2f})")
    ax.axhline(lower, color="#d62728", ls="--", label=f"A not better ({lower:+.2f})")
    ax.axhline(0, color="grey", lw=0.6)
    ax.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
    ax.set_xlabel("pairs played")
    ax.set_ylabel("log-likelihood ratio")
    ax.set_title(title)
    ax.legend(fontsize=8, loc="best")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
