"""Players: one mineflayer bot process per player running sandboxed agent code (see docs/players.md)."""

from pillagerbench.players.player import Player, PlayerError

__all__ = ["Player", "PlayerError"]
