"""A series (one match of consecutive episodes) as its run directory records it: its spec, and the
series of any run directory, an experiment's or a plain `pillagerbench run`'s."""

from __future__ import annotations

import copy
import json
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any

from pillagerbench.config.schema import RunConfig
from pillagerbench.rundir.directory import RunDir
from pillagerbench.rundir.experiment import read_experiment
from pillagerbench.rundir.manifest import stored


@dataclass
class SeriesSpec:
    id: str  # unique in the experiment, also the series' directory name
    index: int
    design: (
        str  # the experiment's design (experiments/spec.py DESIGNS; "run" for a plain run, "league" for a league round)
    )
    scenario: str
    red: str  # the red row label (team name or variant label)
    blue: str  # the blue column label
    red_team: str
    blue_team: str
    episodes: int
    seed: int
    config: RunConfig  # the match's full resolved config, typed (its records store it: manifest.stored)
    checkpoint: dict[str, Any] = field(default_factory=dict)  # side -> {"series": id, "episode": k} | {"path": p}
    checkpoint_every: int | None = None  # keep checkpoints after episodes every, 2·every, ... (1-based count)
    checkpoint_at: list[int] = field(default_factory=list)  # keep checkpoints after these episode indices
    variant: str | None = None
    repetition: int = 0
    group: str | None = None  # e.g. "same"/"different" (adaptation), "after 5" (self-play evaluation)
    group_x: float | None = None  # a number for the group (episodes of experience), for plots
    episode_offset: int = 0  # episodes of experience before this series (learning curves)

    @property
    def after(self) -> list[str]:
        """Series that must finish first (their checkpoints are this one's start)."""
        return sorted({c["series"] for c in self.checkpoint.values() if "series" in c})

    def keeps_checkpoint(self, episode: int) -> bool:
        every = self.checkpoint_every
        return episode in self.checkpoint_at or bool(every and (episode + 1) % every == 0)

    def to_dict(self) -> dict:
        """The spec as experiment.json records it: every field, the config as stored."""
        own = {f.name: copy.deepcopy(getattr(self, f.name)) for f in fields(self) if f.name != "config"}
        return {**own, "config": stored(self.config)}

    @classmethod
    def from_dict(cls, d: dict) -> SeriesSpec:
        """The spec of a recorded dict (experiment.json's series; the config typed here, once)."""
        known = {k: v for k, v in d.items() if k in cls.__dataclass_fields__ and k != "config"}
        return cls(**known, config=RunConfig.of(d["config"]))


def write_series(rundir: RunDir, spec: SeriesSpec) -> None:
    """An experiment's series directory's series.json: its spec without the config (the manifest has it)."""
    rundir.series_path.write_text(json.dumps({k: v for k, v in spec.to_dict().items() if k != "config"}, indent=1))


def read_series(
    run_dir: str | Path,
) -> tuple[str, list[tuple[SeriesSpec, Path]]] | None:
    """The name and the series (spec and directory) of a run directory: an experiment's, or the one
    series of a plain run (its config as a series': RunConfig.for_series); None for a directory that is not a run."""
    rundir = RunDir(run_dir)
    if rundir.is_experiment():
        data = read_experiment(rundir.path)  # whichever version wrote it
        specs = [SeriesSpec.from_dict(s) for s in data.series]
        return data.name, [(s, rundir.series_dir(s.id)) for s in specs]
    manifest = rundir.manifest()
    if manifest is None:
        return None
    config = RunConfig.of(manifest.config).for_series()
    return "run", [(plain_series(config, rundir.path.name), rundir.path)]


def plain_series(config: RunConfig, name: str) -> SeriesSpec:
    """The one series of a plain run (design "run", named as its directory) from its match config:
    the same whether the run is started or resumed."""
    red, blue = config.red.name, config.blue.name
    return SeriesSpec(
        id=name,
        index=0,
        design="run",
        scenario=config.scenario.name,
        red=red,
        blue=blue,
        red_team=red,
        blue_team=blue,
        episodes=config.episodes,
        seed=config.seed,
        config=config,
    )
