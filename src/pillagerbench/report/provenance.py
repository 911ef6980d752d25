"""What the report is made of: one row per run directory, read from its manifests (the run's
manifest.json and each series' own): git revision (12 characters), seeds, episode length, episodes used of those
planned, the LLM teams' models, the entrants of its episodes (label and id: metrics/entrants.py), scoring
and protocol. Distinct values are joined with ", "."""

from __future__ import annotations

import pandas as pd

from pillagerbench.config.sides import SIDES
from pillagerbench.metrics.columns import Col
from pillagerbench.metrics.runs import Runs, SeriesInfo
from pillagerbench.rundir import Manifest, RunDir
from pillagerbench.teams import TEAMS

COLUMNS = [
    "run",
    "what",
    "created",
    "revision",
    "suite",
    "scenarios",
    "seeds",
    "episode_length",
    "episodes",
    "models",
    "entrants",
    "scoring",
    "protocol",
]


def _distinct(values, empty: str = "–") -> str:
    return ", ".join(dict.fromkeys(str(v) for v in values if v not in (None, ""))) or empty


def seed_range(seeds: list[int]) -> str:
    """0, 1, 2, 3 -> "0–3"; gaps are listed."""
    s = sorted(set(seeds))
    if len(s) > 2 and s == list(range(s[0], s[-1] + 1)):
        return f"{s[0]}–{s[-1]}"
    return ", ".join(map(str, s)) or "–"


def models(s: SeriesInfo) -> list[str]:
    """`label: provider model` for each side of the series whose team uses an LLM (a team the
    registry does not know is not imported to find out), with TactiCrafter's per-role models."""
    out = []
    for side, label in (("red", s.red), ("blue", s.blue)):
        team = s.config.side(side)
        cls = TEAMS.get(team.name)
        if cls is None or not cls.uses_llm:
            continue
        llm = s.config.llm_of(side)
        roles = {r: o["model"] for r, o in (team.options.get("roles") or {}).items() if (o or {}).get("model")}
        extra = f" ({', '.join(f'{r}: {m}' for r, m in roles.items())})" if roles else ""
        out.append(f"{label}: {llm.provider or '?'} {llm.model or '?'}{extra}")
    return out


def entrants(df: pd.DataFrame) -> list[str]:
    """`label (id)` of every entrant in these episodes, red before blue, each once."""
    return [f"{label} ({i})" for side in SIDES for label, i in zip(df[Col.entrant(side)], df[Col.entrant_id(side)])]


def provenance(runs: Runs) -> pd.DataFrame:
    df = runs.episodes
    rows = []
    for run in runs.runs:
        top = RunDir(runs.roots.get(run, run)).manifest() or Manifest()
        series = [s for s in runs.series if s.run == run]
        used = int((df[Col.RUN] == str(run)).sum()) if len(df) else 0
        rows.append(
            {
                "run": str(run),
                "what": f"experiment {top.experiment}" if top.experiment else "run",
                "created": top.created if "created" in top.model_fields_set else "–",
                "revision": _distinct(
                    str(r)[:12]
                    for r in [top.git_revision] + [s.manifest.git_revision for s in series if s.manifest]
                    if r
                ),
                "suite": _distinct(df.loc[df[Col.RUN] == str(run), Col.SUITE]) if len(df) else "–",  # its episodes'
                "scenarios": _distinct(f"{s.scenario} v{s.version}" for s in series),
                "seeds": seed_range([s.config.seed for s in series]),
                "episode_length": _distinct(f"{s.episode_length:g} s" for s in series),
                "episodes": f"{used} of {sum(s.episodes for s in series)}",
                "models": _distinct((m for s in series for m in models(s)), "no LLM team"),
                "entrants": _distinct(entrants(df[df[Col.RUN] == str(run)]) if len(df) else []),
                "scoring": _distinct(s.config.scoring for s in series),
                "protocol": _distinct(s.config.protocol for s in series),
            }
        )
    return pd.DataFrame(rows, columns=COLUMNS)
