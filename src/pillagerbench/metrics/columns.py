"""The table of episodes that metrics hands the report (`Runs.episodes`, and `Runs.spoiled` with the same
columns): one row per episode, each column named once here. metrics/runs.py writes every row with these
names (`EPISODE_COLUMNS` is their order) and the report reads them by these names, never by a string of
its own.

Per side (`red`, `blue`): the entrant's name (`red`), its team (`red_team`), final points as the run's
scoring and scaled (`red_score`), raw (`red_raw`), by every scoring recorded (`red_clean`,
`red_upstream`) and over time (`red_t`); the entrant columns of metrics/entrants.py (`red_entrant`,
`red_entrant_id`, `red_name`)."""

from __future__ import annotations

from typing import Final

from pillagerbench.config.sides import SIDES
from pillagerbench.match import SCORINGS


class Col:
    """The columns of the table of episodes."""

    RUN: Final = "run"  # the run's name (a bundle's: the path it was exported from)
    DIR: Final = "dir"  # the episode's directory
    SERIES: Final = "series"
    SCENARIO: Final = "scenario"
    VERSION: Final = "version"  # the scenario's version
    EPISODE_LENGTH: Final = "episode_length"
    RED: Final = "red"  # the red entrant's name, which every table groups by
    BLUE: Final = "blue"
    RED_TEAM: Final = "red_team"
    BLUE_TEAM: Final = "blue_team"
    DESIGN: Final = "design"
    VARIANT: Final = "variant"
    REPETITION: Final = "repetition"
    GROUP: Final = "group"  # adaptation's same/different, self-play's "after k"; NaN for ordinary series
    GROUP_X: Final = "group_x"
    EPISODE: Final = "episode"
    INDEX: Final = "index"  # the episode's place among its series' used episodes (learning curves)
    RED_RAW: Final = "red_raw"
    BLUE_RAW: Final = "blue_raw"
    SCALE: Final = "scale"
    RED_SCORE: Final = "red_score"
    BLUE_SCORE: Final = "blue_score"
    SCORING: Final = "scoring"
    SUITE: Final = "suite"
    STAMP: Final = "stamp"
    RULES: Final = "rules"
    CONDITIONS: Final = "conditions"
    LAYOUT: Final = "layout"
    SEED: Final = "seed"  # the episode's seed: with its layout, the world it was played in (metrics/paired.py)
    SPLIT: Final = "split"
    TEAM_PROTOCOL: Final = "team_protocol"
    ITERATIONS: Final = "iterations"  # mean code iterations of the red team
    PROBLEMS: Final = "problems"
    SERVER_TPS: Final = "server_tps"
    LAGGED: Final = "lagged"
    LAG_REASON: Final = "lag_reason"
    T: Final = "t"  # the seconds of the score timeline
    RED_T: Final = "red_t"
    BLUE_T: Final = "blue_t"

    @staticmethod
    def name(side: str) -> str:
        """A side's entrant name (`red`, `blue`)."""
        return side

    @staticmethod
    def team(side: str) -> str:
        return f"{side}_team"

    @staticmethod
    def score(side: str) -> str:
        return f"{side}_score"

    @staticmethod
    def raw(side: str) -> str:
        return f"{side}_raw"

    @staticmethod
    def by_scoring(side: str, scoring: str) -> str:
        """A side's final points by one scoring (NaN when the episode did not record it)."""
        return f"{side}_{scoring}"

    @staticmethod
    def over_time(side: str) -> str:
        return f"{side}_t"

    @staticmethod
    def entrant(side: str) -> str:
        """A side's entrant label (metrics/entrants.py)."""
        return f"{side}_entrant"

    @staticmethod
    def entrant_id(side: str) -> str:
        return f"{side}_entrant_id"

    @staticmethod
    def series_name(side: str) -> str:
        """The name the series gave the side (a variant label, a league entrant's name)."""
        return f"{side}_name"


ENTRANT_COLUMNS: Final = tuple(
    c for side in SIDES for c in (Col.entrant(side), Col.entrant_id(side), Col.series_name(side))
)
EPISODE_COLUMNS: Final = (
    *(Col.RUN, Col.DIR, Col.SERIES, Col.SCENARIO, Col.VERSION, Col.EPISODE_LENGTH, Col.RED, Col.BLUE),
    *ENTRANT_COLUMNS,
    *(Col.RED_TEAM, Col.BLUE_TEAM, Col.DESIGN, Col.VARIANT, Col.REPETITION, Col.GROUP, Col.GROUP_X),
    *(Col.EPISODE, Col.INDEX, Col.RED_RAW, Col.BLUE_RAW, Col.SCALE, Col.RED_SCORE, Col.BLUE_SCORE),
    *(Col.SCORING, Col.SUITE, Col.STAMP, Col.RULES, Col.CONDITIONS, Col.LAYOUT, Col.SEED, Col.SPLIT),
    *(Col.by_scoring(side, mode) for mode in SCORINGS for side in SIDES),
    *(Col.TEAM_PROTOCOL, Col.ITERATIONS, Col.PROBLEMS, Col.SERVER_TPS, Col.LAGGED, Col.LAG_REASON),
    *(Col.T, Col.RED_T, Col.BLUE_T),
)
