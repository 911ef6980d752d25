"""The arena: the Minecraft 1.16.5 server we ship (flying-squid + our plugins) and its control channel."""

from pillagerbench.server.control import ControlChannel, ControlError
from pillagerbench.server.process import ArenaServer, ArenaServerError

__all__ = ["ArenaServer", "ArenaServerError", "ControlChannel", "ControlError"]
