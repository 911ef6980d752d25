"""A match (`match.py`) made of parts: the game loop (`game.py`), what follows a game (`parts.py`:
replay, live view, world log, lag meter, progress), the scorings (`scoring.py`), and the player
handle a team gets (`player.py`); the checks of a configuration's groups (`validate.py`); upstream's quirks are `pillagerbench/scenarios/upstream.py`."""

from pillagerbench.match import validate  # registers the checks of the groups (config/validate.py)
from pillagerbench.match.match import Match
from pillagerbench.match.scoring import SCORINGS

__all__ = ["SCORINGS", "Match", "validate"]
