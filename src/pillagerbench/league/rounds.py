"""A league's matches: one experiment run directory per round, `LEAGUE_DIR/matches/round_NNN/`
(experiment.json, series/<id>/ ... as any experiment, so parallel play, Ray and resume work
unchanged), plus `league.json`: the game overrides the round was played with and the identity of
each entrant it involved: its entrant id (rundir/entrant.py: team, models, options; league/compose.py
`entrant_of_entry`), or in a round played before the entrant type the 16 hex digits of its league.yaml
entry (`RosterEntry.old_fingerprint`), which is checked as it was made. A round whose stamp disagrees
with league.yaml belongs to another league and is refused, never overwritten. Rounds played elsewhere can be handed
over as results bundles (`pillagerbench export ROUND_DIR --out LEAGUE_DIR/matches/NAME.tar.gz`): the
board and the scheduler read them as rounds, their stamps checked the same; the budget counts only
what was played here."""

from __future__ import annotations

import json
from pathlib import Path

from pillagerbench.config.compose import ConfigError
from pillagerbench.config.schema import RunnerConfig
from pillagerbench.experiments.runner import write_experiment
from pillagerbench.experiments.spec import SeriesSpec, slug
from pillagerbench.league.compose import entrant_of_entry, match_config
from pillagerbench.league.schedule import Pairing
from pillagerbench.league.spec import OLD_STAMP, League, RosterEntry
from pillagerbench.league.splits import match_split
from pillagerbench.rundir import RunDir
from pillagerbench.rundir.bundle import bundle_runs

MATCHES = "matches"
STAMP = "league.json"


def round_dirs(league_dir: Path) -> list[Path]:
    """The rounds written so far, in order."""
    return sorted(d for d in (Path(league_dir) / MATCHES).glob("round_*") if RunDir(d).is_experiment())


def handed_over(league_dir: Path) -> list[Path]:
    """Rounds handed over as results bundles (matches/*.tar.gz), in order."""
    return sorted((Path(league_dir) / MATCHES).glob("*.tar.gz"))


def check_stamps(league_dir: Path, league: League, game: tuple[str, ...] | None) -> None:
    """ConfigError when a round was played by another definition of an entrant (or, with `game`,
    other game overrides) than league.yaml / this command gives; handed-over rounds too."""
    unpacked = [disk for bundle in handed_over(league_dir) for disk, _ in bundle_runs(bundle)]
    for d in round_dirs(league_dir) + unpacked:
        if not (d / STAMP).exists():
            raise ConfigError(f"{d}: no {STAMP}; not a round of a league (move it out of {MATCHES}/)")
        stamp = json.loads((d / STAMP).read_text())
        for name, identity in stamp["entrants"].items():
            e = league.entrant(name)
            if e is not None and not _same(e, identity):
                raise ConfigError(
                    f"{d.name}: entrant {name!r} was another team, options or model there than in league.yaml; "
                    "this directory belongs to a different league.yaml (rename the entrant, or use a new league)"
                )
        if game is not None and sorted(stamp["game"]) != sorted(game):
            raise ConfigError(
                f"{d.name} was played with game overrides [{' '.join(stamp['game'])}], this command gives "
                f"[{' '.join(game)}]; play with the same ones (their scores would not compare)"
            )


def _same(entry: RosterEntry, identity: str) -> bool:
    """Whether a round's stamp names this entry: its entrant id, or its old fingerprint (OLD_STAMP)."""
    if len(identity) == OLD_STAMP:
        return entry.old_fingerprint() == identity
    return entrant_of_entry(entry).id == identity


def write_round(
    league_dir: Path,
    league: League,
    pairings: list[Pairing],
    episodes: int,
    game: tuple[str, ...],
    runner: RunnerConfig,
) -> tuple[Path, list[SeriesSpec]]:
    """A new round directory for these pairings; returns it and its series."""
    index = len(round_dirs(league_dir))
    run_dir = Path(league_dir) / MATCHES / f"round_{index:03d}"
    specs = []
    for i, p in enumerate(pairings):  # each match with its side-swapped twin, on the same seed (and layouts)
        for k, (red_name, blue_name) in enumerate(((p.red, p.blue), (p.blue, p.red))):
            red, blue = league.entrant(red_name), league.entrant(blue_name)
            assert red is not None and blue is not None
            cfg = match_config(p.scenario, red, blue, game).updated(
                # test: every episode on a fresh test layout
                {"split": match_split(league.split), "episodes": episodes, "seed": index * 1000 + i}
            )
            specs.append(
                SeriesSpec(
                    id=f"{2 * i + k:03d}_{p.scenario}_{slug(red_name)}_vs_{slug(blue_name)}",
                    index=2 * i + k,
                    design="league",
                    scenario=p.scenario,
                    red=red_name,
                    blue=blue_name,
                    red_team=red.team,
                    blue_team=blue.team,
                    episodes=episodes,
                    seed=cfg.seed,
                    config=cfg,
                )
            )
    involved = {n for p in pairings for n in (p.red, p.blue)}
    entrants = {n: entrant_of_entry(e).id for n in sorted(involved) if (e := league.entrant(n))}
    stamp = {"game": list(game), "entrants": entrants}
    run_dir.mkdir(parents=True, exist_ok=True)
    (run_dir / STAMP).write_text(json.dumps(stamp, indent=1))  # first: a round counts once experiment.json exists
    experiment = {"name": f"league {run_dir.name}", "design": "league"}
    write_experiment(run_dir, runner.model_copy(update={"experiment": experiment}), list(game), specs)
    return run_dir, specs
