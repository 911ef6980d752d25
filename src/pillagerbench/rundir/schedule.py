"""Which episode a series plays next. A series plans `planned` episodes; an episode spoiled on our side
(rundir/faults.py) is kept on disk and a further episode index is played in its place, up to
`retries` times for each planned episode; after that the planned episode is given up and the series
goes on, ending with fewer used episodes. An episode spoiled by a provider outage that the series
waited for (a fault of a kind in `NO_TRY`: experiments/outage.py) is played again and spends no try.
Everything is read from the finished records, so a resumed series goes on exactly where it stopped,
and nothing is overwritten.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from pillagerbench.config.schema import RETRIES  # the config's default `retries` (runs from before the key: this)
from pillagerbench.rundir.directory import RunDir
from pillagerbench.rundir.episode import EpisodeRecord
from pillagerbench.rundir.faults import HARNESS, faults, spoiled

# the faults of ours that spend no try: the provider answered no probe after the episode, and the series
# waited for it before playing the episode again (experiments/outage.py)
NO_TRY: frozenset[str] = frozenset({"provider outage"})


@dataclass
class Progress:
    """A series' episodes so far, against its plan."""

    planned: int
    used: int = 0  # finished and not spoiled: the series' results
    spoiled: int = 0  # finished, spoiled on our side (each replayed while retries last)
    given_up: int = 0  # planned episodes whose every try was spoiled
    next: int | None = 0  # the episode index to play next; None when the series is complete

    @property
    def complete(self) -> bool:
        return self.next is None


def progress(records: dict[int, EpisodeRecord], planned: int, retries: int = RETRIES) -> Progress:
    """Walk the finished records in index order: each planned episode takes tries until one is not
    spoiled or 1 + `retries` were."""
    out = Progress(planned)
    slot = tries = 0
    for index in sorted(records):
        if slot >= planned:
            break
        if any(f.whose == HARNESS and f.kind in NO_TRY for f in faults(records[index])):
            out.spoiled += 1  # waited out: played again, no try spent
            continue
        tries += 1
        if spoiled(records[index]):
            out.spoiled += 1
            if tries <= retries:
                continue
            out.given_up += 1
        else:
            out.used += 1
        slot, tries = slot + 1, 0
    out.next = (max(records) + 1 if records else 0) if slot < planned else None
    return out


def episodes_to_play(rundir: RunDir, planned: int, retries: int = RETRIES) -> Iterator[int]:
    """The episode indices still to play, each decided after the one before it was recorded."""
    while (index := progress(rundir.finished(), planned, retries).next) is not None:
        yield index
