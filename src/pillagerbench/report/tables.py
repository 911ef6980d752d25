"""The report's tables written: each a DataFrame metrics computed (metrics/estimates.py, numbers with
separate 95 % CI columns), as CSV and Markdown ("mean ± ci"); a value resting on one episode says
"n = 1"."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd


# -- output -------------------------------------------------------------------------------------
def _fmt(v) -> str:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "–"
    if isinstance(v, (float, np.floating)):
        return f"{v:.2f}"
    return str(v)


def _cell(mean, ci, single: bool) -> str:
    """ "mean ± ci"; a value without an interval says "n = 1" when it rests on one episode."""
    if _fmt(mean) == "–":
        return "–"
    if ci is None or (isinstance(ci, float) and math.isnan(ci)):
        return f"{_fmt(mean)} (n = 1)" if single else _fmt(mean)
    return f"{_fmt(mean)} ± {_fmt(ci)}"


def display_frame(df: pd.DataFrame) -> pd.DataFrame:
    """Merge `X` and `X_ci` into "mean ± ci" strings for Markdown and HTML."""
    single = list(df["episodes"] == 1) if "episodes" in df.columns else [False] * len(df)
    out = {}
    for c in df.columns:
        if c.endswith("_ci") and c[:-3] in df.columns:
            continue
        if f"{c}_ci" in df.columns:
            out[c] = [_cell(m, ci, one) for m, ci, one in zip(df[c], df[f"{c}_ci"], single)]
        else:
            out[c] = [_fmt(v) for v in df[c]]
    return pd.DataFrame(out, columns=list(out))


def to_markdown(df: pd.DataFrame) -> str:
    shown = display_frame(df)
    cols = list(shown.columns)
    lines = ["| " + " | ".join(cols) + " |", "|" + "|".join("---" for _ in cols) + "|"]
    for _, r in shown.iterrows():
        lines.append("| " + " | ".join(str(r[c]).replace("|", "\\|") for c in cols) + " |")
    if not len(shown):
        lines.append("| " + " | ".join("" for _ in cols) + " |")
    return "\n".join(lines) + "\n"


def write(df: pd.DataFrame, out_dir: Path, name: str, title: str) -> list[Path]:
    csv, md = out_dir / f"{name}.csv", out_dir / f"{name}.md"
    df.to_csv(csv, index=False)
    md.write_text(f"## {title}\n\n" + to_markdown(df))
    return [csv, md]
