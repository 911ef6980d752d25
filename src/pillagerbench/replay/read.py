"""Read a replay recording back, tolerating a run killed mid-episode: a truncated or corrupt file
gives every record up to where it breaks, and says so (`Replay.problem`)."""

from __future__ import annotations

import gzip
import json
import zlib
from dataclasses import dataclass, field
from pathlib import Path

from pillagerbench.replay.record import FORMAT, RECORDING, VERSION
from pillagerbench.rundir import EpisodeDir
from pillagerbench.rundir.names import RECORD


class ReplayError(RuntimeError):
    """No replay can be made (no recording, not a recording, nothing readable): one line."""


@dataclass
class Replay:
    header: dict
    records: list[dict] = field(default_factory=list)  # everything after the header, in file order
    problem: str | None = None  # why the recording ends early (truncated or corrupt), if it does

    @property
    def complete(self) -> bool:
        return self.problem is None and bool(self.records) and self.records[-1].get("type") == "end"

    @property
    def duration(self) -> float:
        times = [r["t"] for r in self.records if isinstance(r.get("t"), (int, float))]
        return max(times, default=0.0)


def find_recording(episode_dir: Path) -> Path:
    episode_dir = Path(episode_dir)
    if not episode_dir.is_dir():
        raise ReplayError(f"{episode_dir} is not a directory (give an episode directory such as RUN_DIR/episode_000)")
    path = episode_dir / RECORDING
    if not path.exists():
        if EpisodeDir(episode_dir).is_episode():
            raise ReplayError(
                f"{episode_dir} has no replay recording ({RECORDING}): it was played before replays were recorded"
            )
        raise ReplayError(f"{episode_dir} is not an episode directory (no {RECORDING}, no {RECORD})")
    return path


def load_replay(episode_dir: Path) -> Replay:
    path = find_recording(episode_dir)
    lines: list[bytes] = []
    problem = None
    try:
        with gzip.open(path, "rb") as f:
            for line in f:
                lines.append(line)
    except (EOFError, OSError, zlib.error) as exc:  # truncated (killed run) or corrupt
        problem = f"the recording is cut short ({type(exc).__name__}: {exc})"
    if lines and not lines[-1].endswith(b"\n"):
        lines.pop()  # a half-written last line
        problem = problem or "the recording ends in the middle of a line"
    records = []
    for i, line in enumerate(lines):
        try:
            records.append(json.loads(line))
        except (json.JSONDecodeError, UnicodeDecodeError):
            problem = f"line {i + 1} of the recording is corrupt; it plays up to there"
            break
    if not records or records[0].get("type") != "header" or records[0].get("format") != FORMAT:
        raise ReplayError(f"{path} is not a readable replay recording ({problem or 'no header'})")
    header = records.pop(0)
    if int(header.get("version", 0)) > VERSION:
        raise ReplayError(f"{path} has replay format version {header['version']}; this PillagerBench reads {VERSION}")
    if problem is None and (not records or records[-1].get("type") != "end"):
        problem = "the recording has no end (the run stopped during the episode); it plays up to where it ends"
    return Replay(header, records, problem)
