"""The run directory: one owner for every path and record a run writes and reads (docs/architecture.md).

`names` spells every file name once. `RunDir` knows every path of a plain run or an experiment's series
directory, appends and reads the episode records as `EpisodeRecord`s (its line in episodes.jsonl, typed;
`from_dict` reads every earlier version), reads and writes the manifest (`Manifest`) and the ledger
offset, tells what is finished and makes a directory consistent after a crash; `EpisodeDir` is one
episode's files (record, timelines, chat, events, ...), `TeamState` a team's saved team.json, and
`LastEpisode` what a team sees of its last episode (`last_seen`, the same after a resume); `faults` says
whose fault a bad episode is and `schedule` which episode a series plays next (a spoiled one is played
again); `read_experiment` reads an experiment's experiment.json (`ExperimentFile`); `bundle` writes and
unpacks results bundles (run directories in one archive). Every writer and reader of run directories
goes through this package, and reads fields, not string keys.
"""

from pillagerbench.rundir.directory import EPISODES, LEDGER, RunDir, episode_index
from pillagerbench.rundir.episode import EpisodeRecord, LastEpisode, TimelinePoint, last_seen_json, winner_of
from pillagerbench.rundir.episode_dir import EpisodeDir
from pillagerbench.rundir.experiment import EXPERIMENT, ExperimentFile, read_experiment, write_experiment_file
from pillagerbench.rundir.faults import HARNESS, TEAM, Fault, faults, spoiled
from pillagerbench.rundir.live import Live, LiveWriter
from pillagerbench.rundir.manifest import Manifest, ScenarioStamp
from pillagerbench.rundir.schedule import RETRIES, Progress, episodes_to_play, progress
from pillagerbench.rundir.series import SeriesSpec, plain_series, read_series, write_series
from pillagerbench.rundir.team_state import TeamState, has_team_state, team_state_path

__all__ = [
    "EPISODES",
    "EXPERIMENT",
    "HARNESS",
    "LEDGER",
    "RETRIES",
    "TEAM",
    "EpisodeDir",
    "EpisodeRecord",
    "ExperimentFile",
    "Fault",
    "LastEpisode",
    "Live",
    "LiveWriter",
    "Manifest",
    "Progress",
    "RunDir",
    "ScenarioStamp",
    "SeriesSpec",
    "TeamState",
    "TimelinePoint",
    "episode_index",
    "episodes_to_play",
    "faults",
    "has_team_state",
    "last_seen_json",
    "plain_series",
    "progress",
    "read_experiment",
    "read_series",
    "spoiled",
    "team_state_path",
    "write_experiment_file",
    "write_series",
    "winner_of",
]
