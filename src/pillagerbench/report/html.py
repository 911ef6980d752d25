"""One self-contained HTML page: every table and figure of the report (figures inlined as base64
PNG), the runs it covers, where σ_blue came from, and what was skipped and why."""

from __future__ import annotations

import base64
import html
from pathlib import Path
from typing import Any

import pandas as pd

from pillagerbench.report.tables import display_frame

STYLE = """
body { font-family: system-ui, sans-serif; margin: 2em auto; max-width: 1200px; color: #222; }
table { border-collapse: collapse; margin: 0.5em 0 1.5em; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.2em 0.6em; text-align: right; }
th { background: #f2f2f2; } td:first-child, th:first-child { text-align: left; }
img { max-width: 100%; border: 1px solid #eee; margin: 0.5em 0 1.5em; }
.note { color: #555; font-size: 0.9em; } code { background: #f6f6f6; }
figure { margin: 0.5em 0 1.5em; } figure img { margin: 0; }
figcaption { color: #444; font-size: 0.9em; margin-top: 0.2em; }
"""


def table_html(df: pd.DataFrame) -> str:
    if not len(df):
        return "<p class='note'>(empty)</p>"
    return display_frame(df).to_html(index=False, escape=True, border=0)


def image_html(path: Path, alt: str, caption: str | None = None) -> str:
    data = base64.b64encode(Path(path).read_bytes()).decode()
    img = f"<img alt='{html.escape(alt)}' src='data:image/png;base64,{data}'>"
    if caption is None:
        return img
    return f"<figure>{img}<figcaption>{html.escape(caption)}</figcaption></figure>"


def page(
    title: str,
    runs: list[Path],
    notes: list[str],
    sections: list[tuple[str, str, Any]],
    toc: bool = False,
    runs_label: str = "Runs",
) -> str:
    """sections: (heading, kind, content) with kind "table" (DataFrame), "image" (Path), "text" or "html"
    (markup as is); `toc`: a table of contents linking every section's heading (`#section-N`)."""
    listed = ", ".join(f"<code>{html.escape(str(r))}</code>" for r in runs) or "none yet"
    parts = [
        f"<!doctype html><html><head><meta charset='utf-8'><title>{html.escape(title)}</title>",
        f"<style>{STYLE}</style></head><body><h1>{html.escape(title)}</h1>",
        f"<p class='note'>{html.escape(runs_label)}: {listed}</p>",
    ]
    if notes:
        parts.append("<ul class='note'>" + "".join(f"<li>{html.escape(n)}</li>" for n in notes) + "</ul>")
    if toc:
        links = "".join(f"<li><a href='#section-{i}'>{html.escape(h)}</a></li>" for i, (h, _, _) in enumerate(sections))
        parts.append(f"<nav id='contents'><h2>Contents</h2><ol>{links}</ol></nav>")
    for i, (heading, kind, content) in enumerate(sections):
        parts.append(f"<h2 id='section-{i}'>{html.escape(heading)}</h2>")
        if kind == "table":
            parts.append(table_html(content))
        elif kind == "image":  # a path, or (path, one-line caption)
            path, caption = content if isinstance(content, tuple) else (content, None)
            parts.append(image_html(path, heading, caption))
        elif kind == "html":
            parts.append(str(content))
        else:
            parts.append(f"<p>{html.escape(str(content))}</p>")
    parts.append("</body></html>")
    return "\n".join(parts)
