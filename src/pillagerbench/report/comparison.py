"""A comparison's report opens with its answer: for every `compare` run among the inputs, its verdict
line (A better, not better, undecided; pairs, episodes, dollars) and a figure of its test's path (the
log-likelihood ratio after each pair between the bounds), before the tables."""

from __future__ import annotations

import html
from pathlib import Path

from pillagerbench.experiments.comparison import Answer, answer, read
from pillagerbench.metrics.runs import Runs
from pillagerbench.report import plots
from pillagerbench.report.sections import Section


def answers(runs: Runs) -> list[tuple[Path, Answer]]:
    """(run name, its answer) of every compare among the runs read, in their order."""
    out = []
    for name in runs.runs:
        c = read(runs.roots[name])
        if c is not None:
            out.append((name, answer(c, runs.roots[name])))
    return out


def sections(found: list[tuple[Path, Answer]], out: Path) -> list[Section]:
    """Per compare: its answer, then its test's path."""
    parts = []
    for i, (name, a) in enumerate(found):
        c, b = a.comparison, a.comparison.bounds
        against = f"each against {c.opponent}" if c.opponent else "head to head"
        text = f"<p><strong>{html.escape(a.line())}</strong></p><p class='note'>{html.escape(str(name))}: {against}</p>"
        title = f"Answer: {c.a} (A) against {c.b} (B)"
        png = plots.sprt_path(list(a.path), b.lower, b.upper, title, out / f"compare_{i}.png")
        caption = (
            f"The sequential test's log-likelihood ratio after each of {len(a.scores)} pair(s): A better once it "
            f"reaches {b.upper:+.2f}, not better at {b.lower:+.2f}, undecided between (cap {c.cap} pairs)."
        )
        parts += [
            Section(title, "html", text),
            Section(f"The test's path: {c.a} against {c.b}", "image", (png, caption)),
        ]
    return parts
