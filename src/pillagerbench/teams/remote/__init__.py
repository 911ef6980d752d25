"""Remote teams: a team in any language behind HTTP (protocol.py; docs/remote-teams.md)."""

from pillagerbench.teams.remote.team import RemoteTeam

__all__ = ["RemoteTeam"]
