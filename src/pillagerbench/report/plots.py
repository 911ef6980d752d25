"""The report's figures (matplotlib, Agg backend, PNG), each with 95 % confidence intervals:

- heatmaps_<scenario>.png   P, S, W, D per red team (rows) and opponent (columns, plus "all")
- timeline_<scenario>.png   mean red score over the episode per red team, shaded CI band
- learning_curve.png        D per episode index (experience) per red team, CI error bars
- groups.png                P/D per group (adaptation same/different, self-play "after k")
- series_scores.png         red and blue score per episode of long series where a team meets itself
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from pillagerbench.metrics.formulas import t_critical
from pillagerbench.report.tables import ALL, opponent_order, red_order

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


def heatmaps(pairs: pd.DataFrame, scenario: str, path: Path) -> Path:
    sd = pairs[pairs["scenario"] == scenario]
    if not len(sd):
        return _empty(path, f"{_title(scenario)}: no episodes")
    rows = red_order(sd)
    cols = [*opponent_order(sd[sd["blue"] != ALL], scenario), ALL]
    fig, axes = plt.subplots(1, 4, figsize=(4.2 * 4, 1.2 + 0.65 * len(rows) + 0.2 * max(0, len(cols) - 5)))
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
                        j, i, text, ha="center", va="center", fontsize=7, color="white" if metric in "PS" else "black"
                    )
        ax.set_xticks(range(len(cols)), cols, rotation=45, ha="right", fontsize=8)
        ax.set_yticks(range(len(rows)), rows, fontsize=8)
        ax.set_title(TITLES[metric], fontsize=10)
        ax.set_xlabel("blue team (opponent)")
        fig.colorbar(im, ax=ax, fraction=0.046, pad=0.04)
    axes[0].set_ylabel("red team")
    fig.suptitle(f"{_title(scenario)} (mean ± 95 % CI)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def timeline(df: pd.DataFrame, scenario: str, path: Path) -> Path:
    sd = df[df["scenario"] == scenario] if len(df) else df
    if not len(sd):
        return _empty(path, f"{_title(scenario)}: no episodes")
    fig, ax = plt.subplots(figsize=(7, 4))
    for red in red_order(sd):
        rd = sd[sd["red"] == red]
        n_t = min(len(t) for t in rd["t"])
        t = rd["t"].iloc[0][:n_t]
        y = np.stack([v[:n_t] for v in rd["red_t"]])
        mean = y.mean(axis=0)
        (line,) = ax.plot(t, mean, label=f"{red} (n={len(y)})")
        if len(y) > 1:
            half = t_critical(len(y) - 1) * y.std(axis=0, ddof=1) / math.sqrt(len(y))
            ax.fill_between(t, mean - half, mean + half, color=line.get_color(), alpha=0.2)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("points (red team)" + (" ×0.1" if scenario == "dash_and_dine" else ""))
    ax.set_title(f"{_title(scenario)}: points over time against all opponents (95 % CI)")
    ax.legend(fontsize=8)
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
    """Red and blue points per episode of the longest series in which a team plays itself (self-play)."""
    if not len(df):
        return _empty(path, "no episodes")
    same = df[(df["red_team"] == df["blue_team"]) & (df["red_team"] != "do_nothing")]
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
