"""The arena: the Minecraft 1.16.5 server we ship (flying-squid + our plugins) and its control channel."""

from pillagerbench.arena.control import ControlChannel, ControlError
from pillagerbench.arena.server import ArenaServer, ArenaServerError

__all__ = ["ArenaServer", "ArenaServerError", "ControlChannel", "ControlError"]
