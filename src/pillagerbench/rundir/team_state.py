"""A team's saved state (team.json in state/episode_NNN/<side>/ and checkpoints/episode_NNN/<side>/):
which team saved it and what `Team.state()` returned, read back by `Team.load_checkpoint`."""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from pillagerbench.rundir import names as N


def team_state_path(directory: str | Path) -> Path:
    """Where a team's state is saved in a checkpoint directory."""
    return Path(directory) / N.TEAM_STATE


def has_team_state(directory: str | Path) -> bool:
    return team_state_path(directory).exists()


@dataclass
class TeamState:
    team: str  # the team's registered name
    state: dict[str, Any] = field(default_factory=dict)  # Team.state(): JSON-serialisable

    def write(self, directory: str | Path) -> Path:
        path = team_state_path(directory)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(asdict(self), indent=1))
        return path

    @classmethod
    def read(cls, directory: str | Path) -> TeamState:
        """The state saved in `directory` (a file without `state` holds none; FileNotFoundError,
        ValueError as json's)."""
        data = json.loads(team_state_path(directory).read_text())
        return cls(team=data.get("team"), state=data.get("state") or {})
