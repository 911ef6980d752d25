"""do_nothing: a team whose players stand still (the reference opponent)."""

from pillagerbench.teams.base import Team


class DoNothing(Team):
    name = "do_nothing"
