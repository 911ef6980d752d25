"""One episode's directory (episode_NNN/ of a run directory): the paths of its files and its files read
and written as what they hold. `RunDir.files(index)` gives it; a part of the match that only knows the
directory it writes into builds it from that path."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from pillagerbench.rundir import names as N
from pillagerbench.rundir.episode import EpisodeRecord, TimelinePoint
from pillagerbench.rundir.whole import replace_json


class EpisodeDir:
    """The files of one episode: record, score timelines, chat, events, world events, game master's log,
    replay, and each side's directory."""

    def __init__(self, path: str | Path):
        self.path = Path(path)

    def __repr__(self) -> str:
        return f"EpisodeDir({str(self.path)!r})"

    @property
    def record_path(self) -> Path:
        """The record beside the episode's files (episode.json)."""
        return self.path / N.RECORD

    def timeline_path(self, scoring: str = "clean") -> Path:
        """The score each second: timeline.json, or timeline_<scoring>.json for another scoring's."""
        return self.path / N.timeline_name(scoring)

    @property
    def chat_path(self) -> Path:
        return self.path / N.CHAT

    @property
    def events_dir(self) -> Path:
        """Each player's events (events/<player>.jsonl)."""
        return self.path / N.EVENTS

    def player_events_path(self, player: str) -> Path:
        """One player's events (events/<player>.jsonl)."""
        return self.events_dir / N.player_events_name(player)

    @property
    def world_events_path(self) -> Path:
        return self.path / N.WORLD_EVENTS

    @property
    def game_master_path(self) -> Path:
        """The game master's log (game_master.json)."""
        return self.path / N.GAME_MASTER

    def task_error_path(self, task: str) -> Path:
        """A background task of the game that raised (<task>.error.txt)."""
        return self.path / f"{task}{N.TASK_ERROR}"

    @property
    def replay_path(self) -> Path:
        return self.path / N.REPLAY

    def side(self, key: str) -> Path:
        """A side's own directory (its team's artefacts)."""
        return self.path / key

    def is_episode(self) -> bool:
        """Whether the directory holds an episode's record or timeline."""
        return self.record_path.exists() or self.timeline_path().exists()

    def record(self) -> EpisodeRecord | None:
        """episode.json, whichever version wrote it; None when missing or unreadable."""
        try:
            return EpisodeRecord.from_dict(json.loads(self.record_path.read_text()))
        except (OSError, ValueError, TypeError):
            return None

    def write_record(self, record: EpisodeRecord) -> None:
        self.path.mkdir(parents=True, exist_ok=True)
        replace_json(self.record_path, record.to_dict(), indent=1)  # a kill leaves no half of one

    def timeline(self, scoring: str = "clean") -> list[TimelinePoint]:
        """The score each second; FileNotFoundError when missing, ValueError when cut short."""
        return json.loads(self.timeline_path(scoring).read_text())

    def chat(self) -> list[str]:
        """The chat lines everyone could read ([] when there are none)."""
        return self.chat_path.read_text().splitlines() if self.chat_path.exists() else []

    def write_chat(self, lines: list[str]) -> None:
        self.chat_path.write_text("\n".join(lines) + ("\n" if lines else ""))

    def write_world_events(self, events: list[dict[str, Any]]) -> None:
        with open(self.world_events_path, "w") as f:
            for e in events:
                f.write(json.dumps(e) + "\n")
