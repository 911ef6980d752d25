"""The entrant of each side of an episode, and the name every table gives it (docs/experiments.md).

An episode's record names its entrants (`red_entrant`, `blue_entrant`: rundir/entrant.py); a record
from before entrants gets them from its series' config (the manifest), computed the same way, so
old run directories and bundles still report. In the episodes table `red` and `blue` are the
entrants' labels, which every table groups by: two entrants never share a row. Should two entrants
read alike (a label hides a long value behind a hash), each label gets `#` and its id's first 6 hex
digits (metrics/rows.py `named`). The name the series gave the side (an experiment's variant label, a league entrant's name)
stays in `red_name` and `blue_name`.
"""

from __future__ import annotations

from typing import Any

from pillagerbench.config.schema import RunConfig
from pillagerbench.metrics.columns import SIDES, Col
from pillagerbench.rundir.entrant import Entrant
from pillagerbench.teams.entrant import entrant_of


def series_entrants(config: RunConfig) -> dict[str, Entrant]:
    """Each side's entrant under a series' resolved config (for records from before entrants)."""
    return {side: entrant_of(config, side) for side in SIDES}


def columns(recorded: dict[str, Entrant | None], derived: dict[str, Entrant], names: dict[str, str]) -> dict[str, Any]:
    """An episode's entrant columns: `<side>_entrant` (label), `<side>_entrant_id`, `<side>_name`; the
    recorded entrant, else the derived one, else (no config to derive from) the series' name."""
    out: dict[str, Any] = {}
    for side in SIDES:
        e = recorded.get(side) or derived.get(side)
        label, id_ = (e.label, e.id) if e is not None else (names[side], names[side])
        out |= {Col.entrant(side): label, Col.entrant_id(side): id_, Col.series_name(side): names[side]}
    return out
