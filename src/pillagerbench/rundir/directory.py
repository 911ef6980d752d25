"""Every path of a run directory (a plain `pillagerbench run` or one series of an experiment), the
episode records in it, and its repair after a crash.

    manifest.json, episodes.jsonl        the config and versions; one line per finished episode
    episode_NNN/                         an episode's files (episode.json, timeline.json, chat.txt, events/, ...)
    llm_calls.jsonl, logs/, server*.log  the LLM ledger, the bots' logs, the server's log
    series.json                          an experiment's series: its SeriesSpec (absent for a plain run)
    state/episode_NNN/<side>/            both teams' state after the last finished episode (for resume)
    state/episode_NNN/ledger_offset      size of llm_calls.jsonl at the end of that episode
    checkpoints/episode_NNN/<side>/      checkpoints kept by the series' policy (team.json, ...)
    live.json                            the episode being played: clock and scores (progress display)
    discarded/                           half-written episodes (and their ledger lines) moved aside on resume

An episode is finished when its line is in episodes.jsonl; the line is written last, after the
episode's files and the teams' state.
"""

from __future__ import annotations

import json
import os
import shutil
import time
from dataclasses import asdict, replace
from pathlib import Path

from pillagerbench.rundir import names as N
from pillagerbench.rundir.episode import EpisodeRecord, LastEpisode
from pillagerbench.rundir.episode_dir import EpisodeDir
from pillagerbench.rundir.live import Live
from pillagerbench.rundir.manifest import Manifest
from pillagerbench.rundir.whole import replace_json

EPISODES = N.EPISODES
LEDGER = N.LEDGER
_EPISODE = N.EPISODE


def episode_index(name: str) -> int | None:
    """The N of a directory named `episode_N` (None for any other name)."""
    if not name.startswith(_EPISODE):
        return None
    try:
        return int(name[len(_EPISODE) :])
    except ValueError:
        return None


def _record(line: str | bytes) -> EpisodeRecord:
    """One line of episodes.jsonl: ValueError when it is not whole JSON (cut by a crash); a whole line
    that is no record is an error of its own (KeyError), never taken for a torn one."""
    data = json.loads(line)
    return EpisodeRecord.from_dict({**data, "episode": int(data["episode"])})


class RunDir:
    """One run directory: its paths, its records, its repair."""

    def __init__(self, path: str | Path):
        self.path = Path(path)

    def __repr__(self) -> str:
        return f"RunDir({str(self.path)!r})"

    # --- paths -------------------------------------------------------------------------------------

    @property
    def episodes_path(self) -> Path:
        return self.path / EPISODES

    @property
    def ledger_path(self) -> Path:
        return self.path / LEDGER

    @property
    def live_path(self) -> Path:
        return self.path / N.LIVE

    @property
    def series_error_path(self) -> Path:
        """A series that raised: its traceback."""
        return self.path / N.SERIES_ERROR

    @property
    def series_path(self) -> Path:
        return self.path / N.SERIES

    @property
    def manifest_path(self) -> Path:
        return self.path / N.MANIFEST

    @property
    def experiment_path(self) -> Path:
        """An experiment's top: experiment.json (read it with `read_experiment`)."""
        return self.path / N.EXPERIMENT

    @property
    def calibration_path(self) -> Path:
        """σ_blue measured from this run (calibration.json, written by `pillagerbench calibrate`)."""
        return self.path / N.CALIBRATION

    def series_dir(self, series_id: str) -> Path:
        """One series of an experiment."""
        return self.path / N.SERIES_DIR / series_id

    def all_series(self) -> list[Path]:
        """Every series directory of an experiment (written so far)."""
        return sorted(p for p in (self.path / N.SERIES_DIR).glob("*") if p.is_dir())

    def is_experiment(self) -> bool:
        return self.experiment_path.exists()

    def manifest(self) -> Manifest | None:
        """manifest.json, whichever version wrote it (None when the run has not written one yet)."""
        if not self.manifest_path.exists():
            return None
        return Manifest.model_validate(json.loads(self.manifest_path.read_text()))

    def write_manifest(self, manifest: Manifest) -> None:
        self.path.mkdir(parents=True, exist_ok=True)
        replace_json(self.manifest_path, manifest.to_dict(), indent=1)  # a kill leaves no half of one

    def episode(self, index: int) -> Path:
        return self.path / f"{_EPISODE}{index:03d}"

    def files(self, index: int) -> EpisodeDir:
        """An episode's directory: its files' paths, read and written as what they hold."""
        return EpisodeDir(self.episode(index))

    def record_path(self, index: int) -> Path:
        """An episode's record beside its files (episode.json)."""
        return self.files(index).record_path

    def timeline_path(self, index: int, scoring: str = "clean") -> Path:
        """An episode's score each second: timeline.json, or timeline_<scoring>.json for another scoring's."""
        return self.files(index).timeline_path(scoring)

    def state(self, index: int) -> Path:
        return self.path / N.STATE / f"{_EPISODE}{index:03d}"

    def state_dirs(self) -> list[tuple[int, Path]]:
        """(index, path) of every episode's saved state (state/episode_N)."""
        parent = self.path / N.STATE
        return self.episode_dirs(parent) if parent.exists() else []

    def ledger_offset_path(self, index: int) -> Path:
        """The ledger's length when an episode's state was saved (state/episode_N/ledger_offset)."""
        return self.state(index) / N.LEDGER_OFFSET

    def checkpoint(self, index: int, side: str) -> Path:
        return self.path / N.CHECKPOINTS / f"{_EPISODE}{index:03d}" / side

    def logs_dir(self) -> Path:
        """The bots' logs."""
        return self.path / N.LOGS

    def episode_dirs(self, parent: Path | None = None) -> list[tuple[int, Path]]:
        """(index, path) of every episode_N directory under `parent` (default: the run directory), in order."""
        parent = self.path if parent is None else parent
        found = [(episode_index(d.name), d) for d in sorted(parent.glob(f"{_EPISODE}*")) if d.is_dir()]
        return [(i, d) for i, d in found if i is not None]

    # --- records -----------------------------------------------------------------------------------

    def append(self, record: EpisodeRecord) -> None:
        """Add an episode's line to episodes.jsonl (flushed to disk: it marks the episode finished)."""
        self.path.mkdir(parents=True, exist_ok=True)
        with open(self.episodes_path, "a") as f:
            f.write(json.dumps(record.to_dict()) + "\n")
            f.flush()
            os.fsync(f.fileno())

    def write_episode(self, record: EpisodeRecord) -> None:
        """The record beside the episode's files (episode.json), finished or failed."""
        self.files(record.episode).write_record(record)

    def read(self) -> tuple[dict[int, EpisodeRecord], int, int]:
        """Finished episodes by index from episodes.jsonl, the byte length of its good lines, and its size."""
        if not self.episodes_path.exists():
            return {}, 0, 0
        data = self.episodes_path.read_bytes()
        finished: dict[int, EpisodeRecord] = {}
        good = 0
        for raw in data.splitlines(keepends=True):
            if not raw.endswith(b"\n"):
                break  # cut by a crash
            try:
                rec = _record(raw)
            except ValueError:
                break
            finished.setdefault(rec.episode, rec)
            good += len(raw)
        return finished, good, len(data)

    def read_lenient(self) -> tuple[dict[int, EpisodeRecord], list[int]]:
        """Every whole line of episodes.jsonl by episode (the first one wins) and the numbers of the
        lines that are not whole: what a reader of a damaged run uses, where `read` stops at the first
        bad line as a resume must."""
        finished: dict[int, EpisodeRecord] = {}
        bad: list[int] = []
        if not self.episodes_path.exists():
            return finished, bad
        for n, line in enumerate(self.episodes_path.read_text().splitlines(), 1):
            if not line.strip():
                continue
            try:
                rec = _record(line)
            except ValueError:
                bad.append(n)
                continue
            finished.setdefault(rec.episode, rec)
        return finished, bad

    def finished(self) -> dict[int, EpisodeRecord]:
        return self.read()[0]

    def records(self) -> list[EpisodeRecord]:
        """Every line of episodes.jsonl in order (a torn last line left out)."""
        return list(self.finished().values())

    def last_seen(self, record: EpisodeRecord) -> LastEpisode:
        """What a team sees of a finished episode: its record and what its directory holds. The match
        builds it after each episode from the record it wrote; a resumed series rebuilds it from the
        same record read back, so both give the same."""
        files = self.files(record.episode)
        return {
            "record": EpisodeRecord.from_dict(json.loads(json.dumps(record.to_dict()))),  # as written
            "events_dir": str(files.events_dir),
            "timeline": files.timeline() if files.timeline_path().exists() else [],
            "chat": files.chat(),
        }

    def ledger_offset(self, index: int) -> int | None:
        """The ledger's length after an episode (None for a run from before it was kept)."""
        path = self.ledger_offset_path(index)
        return int(path.read_text()) if path.exists() else None

    def write_ledger_offset(self, index: int) -> None:
        """The ledger's length now, kept beside the episode's state (what a resume truncates it to)."""
        size = self.ledger_path.stat().st_size if self.ledger_path.exists() else 0
        self.ledger_offset_path(index).write_text(str(size))

    def free_server_log(self) -> Path:
        """A server log that does not overwrite an earlier one (server.log, server.1.log, ...): a
        resumed series keeps the log of the run that was killed."""
        path, n = self.path / f"{N.SERVER_LOG}.log", 1
        while path.exists():
            path, n = self.path / f"{N.SERVER_LOG}.{n}.log", n + 1
        return path

    def note_resume(self, finished: list[int], discarded: list[str], suite: str) -> None:
        """One line in resumes.jsonl: when the series was resumed, what it had finished, what it discarded,
        and the suite it plays on under (the manifest keeps the one it began under)."""
        line = {"ts": time.strftime("%Y-%m-%dT%H:%M:%S%z"), "finished": finished, "discarded": discarded}
        with open(self.path / N.RESUMES, "a") as f:
            f.write(json.dumps({**line, "suite": suite}) + "\n")

    def resumed_suites(self) -> list[str]:
        """The suites this series was resumed under (resumes.jsonl; a resume from before says none)."""
        path = self.path / N.RESUMES
        lines = path.read_text().splitlines() if path.exists() else []
        found = []
        for line in lines:
            try:
                suite = json.loads(line).get("suite")
            except (ValueError, AttributeError):
                continue
            if isinstance(suite, str):
                found.append(suite)
        return found

    def write_live(self, status: Live) -> None:
        replace_json(self.live_path, asdict(replace(status, ts=time.time())))

    def read_live(self) -> Live | None:
        """The episode being played (None when none is, or live.json is being replaced)."""
        try:
            return Live.of(json.loads(self.live_path.read_text()))
        except (OSError, ValueError, TypeError):
            return None

    # --- repair ------------------------------------------------------------------------------------

    def _discard(self, path: Path, note: list[str]) -> None:
        target = self.path / N.DISCARDED / f"{path.name}.{time.strftime('%Y%m%d-%H%M%S')}"
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.move(str(path), str(target))
        note.append(f"{path.name} -> discarded/{target.name}")

    def _keep_tail(self, name: str, data: bytes) -> None:
        (self.path / N.DISCARDED).mkdir(exist_ok=True)
        (self.path / N.DISCARDED / f"{name}.tail.{time.strftime('%Y%m%d-%H%M%S')}").write_bytes(data)

    def recover(self) -> tuple[dict[int, EpisodeRecord], list[str]]:
        """Make the directory consistent after a crash; returns finished episodes and what was discarded:
        a torn last line, the unfinished episodes' directories, state and checkpoints, and their ledger lines."""
        note: list[str] = []
        finished, good, size = self.read()
        if good < size:
            self._keep_tail(EPISODES, self.episodes_path.read_bytes()[good:])
            with open(self.episodes_path, "r+b") as f:
                f.truncate(good)
            note.append(f"a torn last line of {EPISODES} ({size - good} bytes)")
        for i, d in self.episode_dirs():
            if i not in finished:
                self._discard(d, note)
        for parent in (self.path / N.STATE, self.path / N.CHECKPOINTS):
            for i, d in self.episode_dirs(parent) if parent.exists() else []:
                if i not in finished:
                    shutil.rmtree(d, ignore_errors=True)
        if self.ledger_path.exists():
            kept = self.ledger_offset(max(finished)) if finished else 0
            offset = self.ledger_path.stat().st_size if kept is None else kept  # older run: keep all
            if self.ledger_path.stat().st_size > offset:
                data = self.ledger_path.read_bytes()
                self._keep_tail(LEDGER, data[offset:])
                with open(self.ledger_path, "r+b") as fh:
                    fh.truncate(offset)
                calls = data[offset:].count(b"\n")
                note.append(f"{LEDGER}: {calls} call(s) of the unfinished episode")
        self.live_path.unlink(missing_ok=True)
        return finished, note
