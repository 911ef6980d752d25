"""An episode's record (its line in episodes.jsonl and its episode.json) and what a team sees of a
finished episode (`TeamContext.last_episode`)."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field, fields
from typing import Any, NotRequired, TypedDict

from pillagerbench.rundir.entrant import Entrant
from pillagerbench.stats.result import DREW, LOST, WON, result
from pillagerbench.suite.conditions import RULES, stamp, suite_defaults
from pillagerbench.suite.version import UNVERSIONED, current


@dataclass
class EpisodeRecord:
    scenario: str
    red: str
    blue: str
    episode: int
    red_score: float | None = None
    blue_score: float | None = None
    winner: str | None = None
    duration_s: float = 0.0  # wall time of the whole episode (reset .. post-game)
    status: str = "ok"  # OK | FAILED
    error: str | None = None
    reset_s: float = 0.0
    pre_game_s: dict[str, float] = field(default_factory=dict)
    game_s: float = 0.0
    iterations: dict[str, list[int]] = field(default_factory=dict)
    seed: int = 0
    player_order: list[str] = field(default_factory=list)  # the server's player order this episode
    server_tps: float | None = None  # game ticks per wall second during the game (20 = no server lag)
    bot_lag: dict[str, dict | None] = field(
        default_factory=dict
    )  # player -> physics-tick lag in the game (host/machine.py)
    lagged: bool = False  # played under lag: a threshold of host/machine.py crossed (scores may be low for it)
    lag_reason: str | None = None
    # stalled on our machine: the lockstep world went on without an idle bot at the server's wall-clock
    # limit, or a bot was restarted for the machine's sake (starved of CPU, or it did not stop in time)
    stalled: bool = False
    stall_reason: str | None = None
    problems: dict[str, list[str]] = field(default_factory=dict)  # side -> what failed throughout
    refusals: dict[str, int] = field(default_factory=dict)  # actions the server refused, per player (fair play)
    scoring: str = "clean"  # which of `scores` red_score/blue_score are (config `scoring`)
    scores: dict[str, dict[str, float]] = field(default_factory=dict)  # scoring -> side -> final score
    protocol: str = "pillagerbench"  # the LLM teams' loop (config `protocol`)
    runs: dict[str, int] = field(default_factory=dict)  # code runs started per player (upstream's steps)
    layout: str | int = "paper"  # the arena's layout: "paper", a seed, or a layout file (docs/layouts.md)
    split: str = "paper"  # paper | dev | test | custom (scenarios/layout.py split_of)
    suite: str = field(default_factory=lambda: current()["label"])  # the rules it was played under (suite/version.py)
    conditions: dict[str, Any] = field(default_factory=dict)  # rules differing from the suite's (suite/conditions.py)
    # who played each side (rundir/entrant.py), written {label, id, team, models, options}; None in records
    # from before entrants (readers derive it from the series' config: metrics/entrants.py)
    red_entrant: Entrant | None = None
    blue_entrant: Entrant | None = None

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> EpisodeRecord:
        """A record read back, whichever version wrote it: the one place that knows earlier versions.
        Keys added since take their defaults (records before scoring modes were clean-scored, before
        protocols played ours), a record before suite versions is "unversioned", `scores` is filled from
        red_score/blue_score where it was not recorded, null lists and maps are empty, a record before
        entrants has none (its reader derives them from the config); unknown keys are dropped."""
        known = {f.name for f in fields(cls)}
        given = {k: v for k, v in data.items() if k in known and v is not None or k in _NULLABLE}
        for key in ENTRANTS:
            if isinstance(given.get(key), dict):
                given[key] = Entrant.from_dict(given[key])
        rec = cls(**{**_UNNAMED, **given})  # a killed run's line may hold no more than its episode and status
        if not rec.scores and rec.red_score is not None and rec.blue_score is not None:
            rec.scores = {rec.scoring: {"red": rec.red_score, "blue": rec.blue_score}}
        if not data.get("suite"):
            rec.suite = UNVERSIONED
        if "conditions" not in data:  # before conditions were stamped: the rules the record itself names
            rec.conditions = _recorded_rules(rec)
        return rec

    def to_dict(self) -> dict[str, Any]:
        """The record as it is written (episodes.jsonl, episode.json, a remote team's message): its
        fields in their order, each entrant as its dict."""
        out = asdict(self)
        for key in ENTRANTS:
            entrant = getattr(self, key)
            out[key] = entrant.to_dict() if entrant is not None else None
        return out

    @property
    def ok(self) -> bool:
        return self.status == OK

    @property
    def stamp(self) -> str:
        """The suite and the conditions it was played under (conditions.stamp)."""
        return stamp(self.suite, self.conditions)


def _recorded_rules(rec: EpisodeRecord) -> dict[str, Any]:
    defaults = suite_defaults(rec.scenario)
    named = {"scoring": rec.scoring, "protocol": rec.protocol}
    return {k: v for k, v in named.items() if k in RULES and k in defaults and v != defaults[k]}


OK = "ok"
ENTRANTS = ("red_entrant", "blue_entrant")  # the fields that hold an Entrant
FAILED = "failed"
# what a line that names no more than its episode (and status) stands for
_UNNAMED: dict[str, Any] = {"scenario": "", "red": "", "blue": ""}
# keys whose null is a value (not "missing in an earlier version")
_NULLABLE = {"red_score", "blue_score", "winner", "error", "server_tps", "lag_reason", "stall_reason"}


class TimelinePoint(TypedDict):
    """One point of an episode's score timeline: the second and each side's score then (upstream's
    samples also name the line of its rewards file)."""

    t: float
    red: float
    blue: float
    line: NotRequired[int]


class LastEpisode(TypedDict, total=False):
    """What a team sees of its last finished episode: its record, its events directory, its score
    timeline and the world chat ("<player> message" lines, game-master lines plain)."""

    record: EpisodeRecord
    events_dir: str
    timeline: list[TimelinePoint]
    chat: list[str]


def last_seen_json(last: LastEpisode) -> dict[str, Any]:
    """What a team sees of its last episode as JSON (a remote team's message): the record as it is
    written, the rest as it is."""
    out: dict[str, Any] = dict(last)
    if "record" in last:
        out["record"] = last["record"].to_dict()
    return out


def winner_of(red: float, blue: float) -> str:
    return {WON: "red", DREW: "tie", LOST: "blue"}[result(red, blue)]
