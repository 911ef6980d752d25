"""human: a team whose every player is a person playing from the browser (docs/people.md).

The team itself decides nothing: its players are driven by people through the match's page
(people/), on the same bots, under the same rules, as agents' players. Its `play` waits for the whistle.
"""

from pillagerbench.teams.base import Team


class Human(Team):
    name = "human"
