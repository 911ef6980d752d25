"""The names of a run directory's files, each written once: `RunDir` (directory.py) builds every path
from them, and no module outside this package spells one (tests/experiments/test_run_directory.py).

A run directory (a plain run or a series of an experiment) holds the first group; each episode's
directory (episode_NNN/) the second; each side's directory inside it and a team's saved state the
third."""

from __future__ import annotations

# the run directory
EPISODES = "episodes.jsonl"
LEDGER = "llm_calls.jsonl"
MANIFEST = "manifest.json"
SERIES = "series.json"
EXPERIMENT = "experiment.json"
LIVE = "live.json"
RESUMES = "resumes.jsonl"
SERIES_DIR = "series"
STATE = "state"
CHECKPOINTS = "checkpoints"
LOGS = "logs"
DISCARDED = "discarded"
REPORT = "report"
CALIBRATION = "calibration.json"  # σ_blue measured from the run (pillagerbench calibrate)
SERIES_ERROR = "series_error.txt"  # a series that raised: its traceback (experiments/runner.py)
SERVER_LOG = "server"  # server.log, server.1.log, ...
EPISODE = "episode_"  # episode_NNN

# an episode's directory
RECORD = "episode.json"
TIMELINE = "timeline"  # timeline.json (clean scoring), timeline_<scoring>.json
CHAT = "chat.txt"
EVENTS = "events"  # events/<player>.jsonl
WORLD_EVENTS = "world_events.jsonl"
GAME_MASTER = "game_master.json"
REPLAY = "replay.jsonl.gz"
REPLAY_PAGE = "replay.html"
TASK_ERROR = ".error.txt"  # <task>.error.txt: a background task of the game that raised (match/game.py)

# a team's saved state (state/episode_NNN/<side>/, checkpoints/episode_NNN/<side>/) and the ledger's
# length beside it (state/episode_NNN/ledger_offset)
TEAM_STATE = "team.json"
LEDGER_OFFSET = "ledger_offset"


def player_events_name(player: str) -> str:
    """A player's file in an episode's events/ (`<player>.jsonl`)."""
    return f"{player}.jsonl"


def timeline_name(scoring: str) -> str:
    """timeline.json for the clean scoring, timeline_<scoring>.json for another."""
    return f"{TIMELINE}.json" if scoring == "clean" else f"{TIMELINE}_{scoring}.json"
