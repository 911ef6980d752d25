"""The report's replays: every episode of the runs gets its replay page, written from its recording
under the report's directory (`replays/<run>/[series/<id>/]episode_NNN.html`: the run directories
are only read), and a row in the report linking to it; an episode without a recording (played
before replays existed) or with a cut-short one says so."""

from __future__ import annotations

import html
import os
from pathlib import Path

from pillagerbench.replay.page import write_replay
from pillagerbench.replay.read import ReplayError
from pillagerbench.rundir import EpisodeDir, RunDir
from pillagerbench.rundir.episode import FAILED

REPLAYS = "replays"


def run_names(series: list) -> dict[Path, str]:
    """A folder name per run directory: its name, numbered when two runs share one."""
    runs = list(dict.fromkeys(Path(s.run) for s in series))
    names = [r.name for r in runs]
    return {r: r.name if names.count(r.name) == 1 else f"{r.name}_{i}" for i, r in enumerate(runs)}


def write_all(series: list, out: Path) -> tuple[list[dict], list[Path]]:
    """Write every episode's replay page under `out`; rows for the report's table and the pages written."""
    rows, pages = [], []
    folders = run_names(series)
    for s in series:
        if not Path(s.dir).exists():
            continue
        for _, ep in RunDir(s.dir).episode_dirs():
            shown = {side: e.label for side, e in s.entrants.items()}
            red, blue = shown.get("red", s.red), shown.get("blue", s.blue)
            row = {"series": s.id, "episode": ep.name, "red": red, "blue": blue, "score": "", "replay": None}
            rec = EpisodeDir(ep).record()
            if rec is None:
                row["score"] = "unfinished"
            elif rec.red_score is not None:
                row["score"] = f"{rec.red_score:g} – {rec.blue_score:g}"
            elif rec.status == FAILED:
                row["score"] = "failed"
            try:
                where = out / REPLAYS / folders[Path(s.run)] / ep.relative_to(s.root)
                page, replay = write_replay(ep, where.with_name(ep.name + ".html"))
            except ReplayError as exc:
                row["note"] = str(exc).split(": ", 1)[-1] if "no replay recording" in str(exc) else str(exc)
            else:
                pages.append(page)
                row["replay"] = os.path.relpath(page, out)
                row["note"] = replay.problem or ""
            rows.append(row)
    return rows, pages


def table_html(rows: list[dict]) -> str:
    if not rows:
        return "<p class='note'>(no episodes)</p>"
    head = "".join(f"<th>{h}</th>" for h in ("series", "episode", "red", "blue", "points (red – blue)", "replay"))
    body = []
    for r in rows:
        link = (
            f"<a href='{html.escape(r['replay'])}'>replay</a>"
            + (f" <span class='note'>({html.escape(r['note'])})</span>" if r.get("note") else "")
            if r["replay"]
            else f"<span class='note'>{html.escape(r.get('note', ''))}</span>"
        )
        cells = [html.escape(str(r[k])) for k in ("series", "episode", "red", "blue", "score")] + [link]
        body.append("<tr>" + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
    return f"<table><thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>"
