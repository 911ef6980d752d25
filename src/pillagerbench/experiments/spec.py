"""An experiment as a list of series, built from the `experiment` config group.

A *series* is one match: a scenario, a red and a blue team (each with options), a number of
consecutive episodes (the team objects persist between them, so teams learn), an optional
checkpoint to start from and which checkpoints to keep. Every series carries its full resolved
config (the same tree `pillagerbench run` uses), so a series can be played, resumed or shipped to
another machine without composing configs again.

Designs (conf/experiment/*.yaml, key `design`):
- round_robin: every red team of `red_teams` against every blue team of `blue_teams`
- benchmark:   each variant (team + options + model) against every opponent of every scenario
- self_play:   each variant against itself; optionally the red checkpoints then meet every opponent
- adaptation:  train against one opponent, then from that checkpoint one episode against each
- symmetry:    each pairing of `pairings` in both orders (A red vs B blue, B red vs A blue); a
               pairing of a team with itself is one mirror match
- fidelity:    every built-in opponent of each scenario (or `opponents`) against do_nothing, on each
               side of `sides` (blue: the opponent blue, do_nothing red, as upstream measured)
- generalization: each variant against every opponent, on each of its `sides`, on each arena of
               `arenas` (paper: the paper's layout; test: a fresh test layout every episode; dev:
               seeded dev layouts), one series per (opponent, side, arena)
"""

from __future__ import annotations

import functools
import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

from pillagerbench.config.compose import ConfigError
from pillagerbench.config.registry import Registry
from pillagerbench.config.schema import RUNNER_KEYS, ExperimentConfig, RunConfig, Variant
from pillagerbench.config.validate import compose_run
from pillagerbench.rundir import RunDir, SeriesSpec, has_team_state, read_experiment
from pillagerbench.scenarios import make_scenario
from pillagerbench.scenarios.layout import PAPER, SPLITS

# keys of the top-level config that belong to the experiment machinery, not to one series
# command-line overrides an experiment chooses itself for each series
SERIES_GROUPS = ("scenario", "red", "blue", "team@red", "team@blue", "+scenario")


def launch_order(specs: list[SeriesSpec]) -> list[SeriesSpec]:
    """The order series start in when more wait than can run (experiments/runner.py run_all, and the
    plan's schedule): the most work first, game seconds times bots (on the lockstep clock a series
    costs its bots' ticks; on the real clock its game seconds), equal ones in the experiment's order.
    Launched in the experiment's order, a run ended with its longest series alone on an idle core."""
    return sorted(specs, key=lambda s: -s.episodes * s.config.episode_length * _bots(s.scenario))


@functools.cache
def _bots(scenario: str) -> int:
    return len(make_scenario(scenario).all_players())


def builtin_teams(scenario: str) -> list[str]:
    """do_nothing, then the scenario's built-in opponents, in the paper's order."""
    from pillagerbench.teams import TEAMS
    from pillagerbench.teams.scripted import ScriptedTeam

    return ["do_nothing"] + [
        n for n, c in TEAMS.items() if issubclass(c, ScriptedTeam) and c.scenarios and scenario in c.scenarios
    ]


def slug(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "-", str(text)).strip("-") or "x"


def override_key(override: str) -> str:
    return override.partition("=")[0].lstrip("~+")


def check_overrides(argv: list[str]) -> list[str]:
    """The user's overrides that apply to every series; refuse those the experiment chooses itself."""
    keep = []
    for o in argv:
        key = override_key(o)
        top = key.split(".")[0]
        if key in SERIES_GROUPS or top in ("red", "blue", "scenario"):
            raise ConfigError(
                f"{o!r}: an experiment chooses the scenario and both teams of each series itself; use "
                "experiment.team=NAME, experiment.team_options.KEY=VALUE, experiment.scenarios=[...], "
                "experiment.opponents=[...] (round robins: experiment.red_teams / experiment.blue_teams)"
            )
        if top in RUNNER_KEYS or key == "experiment":
            continue
        keep.append(o)
    return keep


class _Composer:
    """Composes one series config per (scenario, red, blue, llm preset), typed; cached."""

    def __init__(self, overrides: list[str]):
        self.overrides = overrides
        self.cache: dict[tuple, RunConfig] = {}

    def __call__(self, scenario: str, red: str, blue: str, llm: str | None) -> RunConfig:
        key = (scenario, red, blue, llm)
        if key not in self.cache:
            own = [o for o in self.overrides if not (llm and override_key(o) == "llm")]
            extra = [f"scenario={scenario}", f"red={red}", f"blue={blue}"] + ([f"llm={llm}"] if llm else [])
            self.cache[key] = compose_run(own + extra).for_series()
        return self.cache[key]


def _known_team(name: Any, key: str) -> str:
    """`name` if a team goes by it; else a ConfigError naming the experiment's key the user set
    (experiment.team=..., not the red=... of the series built from it) and the valid teams."""
    from pillagerbench.teams import find_team

    try:
        find_team(str(name))
    except ConfigError as exc:
        raise ConfigError(f"{key}={name}: {exc}") from None
    return str(name)


def _variants(exp: ExperimentConfig) -> dict[str, tuple[str, Variant]]:
    """label -> (its team, what it plays): each variant's keys over the experiment's own team, options and
    LLM (none given: one variant, the experiment's team, labelled by its name)."""
    own = exp.own()
    if not exp.variants:
        if not own.team:
            raise ConfigError(f"experiment {exp.name!r} needs `team` (experiment.team=NAME)")
        return {(team := _known_team(own.team, "experiment.team")): (team, own)}
    out = {}
    for label, given in exp.variants.items():
        v = given.over(own)
        if not v.team:
            raise ConfigError(f"variant {label!r} of experiment {exp.name!r} names no team")
        key = f"experiment.variants.{label}.team" if "team" in given.model_fields_set else "experiment.team"
        out[str(label)] = (_known_team(v.team, key), v)
    return out


def _opponents(chosen: list[str] | None, key: str, scenario: str) -> list[str]:
    """The teams the experiment's `key` names (each checked), or else the scenario's built-in ones."""
    return [_known_team(t, f"experiment.{key}") for t in chosen] if chosen else builtin_teams(scenario)


def _sides(exp: ExperimentConfig, default: str) -> list[str]:
    """The sides `experiment.sides` names (each blue or red: config/schema.py), or else `default`."""
    return list(exp.sides) if exp.sides else [default]


def _arenas(exp: ExperimentConfig, overrides: list[str]) -> dict[str, int]:
    """`arenas`: split -> episodes per opponent and side (paper: the paper's layout; dev, test: each
    episode on a layout of the split). The experiment chooses each series' layout itself."""
    chosen = [o for o in overrides if override_key(o) in ("layout", "split")]
    if chosen:
        raise ConfigError(
            f"{chosen[0]!r}: experiment {exp.name!r} chooses each series' layout itself; "
            "use experiment.arenas.SPLIT=EPISODES (splits: " + ", ".join(SPLITS) + ")"
        )
    arenas = dict(exp.arenas or {})
    bad = [k for k, n in arenas.items() if k not in SPLITS or isinstance(n, bool) or not isinstance(n, int) or n < 0]
    if bad or not any(arenas.values()):
        raise ConfigError(
            f"experiment.arenas={arenas}: a split ({', '.join(SPLITS)}) -> episodes (an integer ≥ 0) per "
            "opponent and side, at least one above 0, e.g. {paper: 3, test: 3}"
        )
    return {k: n for k, n in arenas.items() if n}


class _Builder:
    def __init__(self, cfg: RunConfig, exp: ExperimentConfig, argv: list[str]):
        self.exp = exp
        self.repetitions = range(exp.repetitions or 1)
        self.compose = _Composer(check_overrides(argv))
        self.series: list[SeriesSpec] = []
        self.seed = cfg.seed

    @property
    def episodes(self) -> int:
        """The episodes of each series (`experiment.episodes`; designs that play it need it)."""
        if self.exp.episodes is None:
            raise ConfigError(f"experiment {self.exp.name!r} needs `episodes` (experiment.episodes=N)")
        return self.exp.episodes

    def add(
        self,
        scenario: str,
        red_team: str,
        blue_team: str,
        episodes: int,
        *,
        red: str | None = None,
        blue: str | None = None,
        variant: Variant | None = None,
        blue_variant: Variant | None = None,
        arena: str | None = None,
        **extra,
    ) -> SeriesSpec:
        own = variant or blue_variant  # the experiment's team: its model is the series' llm
        changes: dict[str, Any] = {
            side: v.team_options or {} for side, v in (("red", variant), ("blue", blue_variant)) if v
        }
        if own is not None:
            changes["llm"] = own.llm_options.given() if own.llm_options else {}
        if arena:  # every episode on the paper's layout, or each on a fresh one of the split
            changes |= {"layout": PAPER, "split": arena}
        extra["variant"] = extra.pop("variant_label", None)
        index = len(self.series)
        red, blue = red or red_team, blue or blue_team
        parts = [f"{index:03d}", scenario, slug(red), "vs", slug(blue)]
        for tag in (extra.get("group"), arena):
            if tag:
                parts.append(slug(tag))
        if len(self.repetitions) > 1:
            parts.append(f"r{extra.get('repetition', 0)}")
        seed = self.seed * 1000 + index
        cfg = self.compose(scenario, red_team, blue_team, own.llm if own is not None else None).updated(
            {**changes, "episodes": int(episodes), "seed": seed}
        )
        spec = SeriesSpec(
            id="_".join(parts),
            index=index,
            design=self.exp.design,
            scenario=scenario,
            red=red,
            blue=blue,
            red_team=red_team,
            blue_team=blue_team,
            episodes=int(episodes),
            seed=seed,
            config=cfg,
            **extra,
        )
        self.series.append(spec)
        return spec

    # -- designs ---------------------------------------------------------------------------------
    def round_robin(self) -> None:
        for rep in self.repetitions:
            for sc in self.exp.scenarios:
                for red in _opponents(self.exp.red_teams, "red_teams", sc):
                    for blue in _opponents(self.exp.blue_teams, "blue_teams", sc):
                        self.add(sc, red, blue, self.episodes, repetition=rep)

    def symmetry(self) -> None:
        pairings = self.exp.pairings or []  # each {scenario, a, b} (config/schema.py Pairing)
        if not pairings:
            raise ConfigError(
                f"experiment {self.exp.name!r} needs `pairings`: a list of {{scenario: NAME, a: TEAM, b: TEAM}}"
            )
        for rep in self.repetitions:
            for p in pairings:
                orders = [(p.a, p.b)] if p.a == p.b else [(p.a, p.b), (p.b, p.a)]
                for red, blue in orders:
                    self.add(p.scenario, red, blue, self.episodes, repetition=rep)

    def fidelity(self) -> None:
        sides = _sides(self.exp, "blue")
        for rep in self.repetitions:
            for sc in self.exp.scenarios:
                for team in _opponents(self.exp.opponents, "opponents", sc):
                    if team == "do_nothing":
                        continue
                    for side in sides:
                        red, blue = ("do_nothing", team) if side == "blue" else (team, "do_nothing")
                        self.add(sc, red, blue, self.episodes, repetition=rep)

    def generalization(self) -> None:
        arenas, sides = _arenas(self.exp, self.compose.overrides), _sides(self.exp, "red")
        for rep in self.repetitions:
            for label, (team, v) in _variants(self.exp).items():
                for sc in self.exp.scenarios:
                    for opponent in _opponents(self.exp.opponents, "opponents", sc):
                        for side in sides:
                            red, blue = (team, opponent) if side == "red" else (opponent, team)
                            sided: dict[str, Any] = (
                                {"red": label, "variant": v} if side == "red" else {"blue": label, "blue_variant": v}
                            )
                            for arena, episodes in arenas.items():
                                self.add(
                                    sc, red, blue, episodes, **sided, arena=arena, variant_label=label, repetition=rep
                                )

    def benchmark(self) -> None:
        for rep in self.repetitions:
            for label, (team, v) in _variants(self.exp).items():
                for sc in self.exp.scenarios:
                    for blue in _opponents(self.exp.opponents, "opponents", sc):
                        self.add(
                            sc,
                            team,
                            blue,
                            self.episodes,
                            red=label,
                            variant=v,
                            variant_label=label,
                            repetition=rep,
                            checkpoint_every=self.exp.checkpoint_every,
                        )

    def self_play(self) -> None:
        every = self.exp.checkpoint_every
        episodes = self.episodes
        for rep in self.repetitions:
            for label, (team, v) in _variants(self.exp).items():
                for sc in self.exp.scenarios:
                    play = self.add(
                        sc,
                        team,
                        team,
                        episodes,
                        red=label,
                        blue=label,
                        variant=v,
                        blue_variant=v,
                        variant_label=label,
                        repetition=rep,
                        checkpoint_every=every,
                    )
                    if not self.exp.evaluate:
                        continue
                    stages = [0] + (list(range(every, episodes + 1, every)) if every else [episodes])
                    for k in stages:
                        ckpt = {"red": {"series": play.id, "episode": k - 1}} if k else {}
                        play.checkpoint_at = sorted(set(play.checkpoint_at) | ({k - 1} if k else set()))
                        for blue in _opponents(self.exp.opponents, "opponents", sc):
                            self.add(
                                sc,
                                team,
                                blue,
                                1,
                                red=label,
                                variant=v,
                                variant_label=label,
                                repetition=rep,
                                checkpoint=ckpt,
                                group=f"after {k}",
                                group_x=k,
                                episode_offset=k,
                            )

    def adaptation(self) -> None:
        train = self.exp.train_episodes
        from_run = self.exp.from_run
        for rep in self.repetitions:
            for label, (team, v) in _variants(self.exp).items():
                for sc in self.exp.scenarios:
                    opponents = _opponents(self.exp.opponents, "opponents", sc)
                    for trained_on in opponents:
                        if from_run:
                            ckpt: dict[str, dict[str, Any]] = {
                                "red": {
                                    "path": str(find_checkpoint(Path(from_run), sc, label, trained_on, rep, train - 1))
                                }
                            }
                        else:
                            t = self.add(
                                sc,
                                team,
                                trained_on,
                                train,
                                red=label,
                                variant=v,
                                variant_label=label,
                                repetition=rep,
                                checkpoint_at=[train - 1],
                                group="training",
                            )
                            ckpt = {"red": {"series": t.id, "episode": train - 1}}
                        for blue in opponents:
                            group = "same" if blue == trained_on else "different"
                            self.add(
                                sc,
                                team,
                                blue,
                                1,
                                red=label,
                                variant=v,
                                variant_label=label,
                                repetition=rep,
                                checkpoint=ckpt,
                                group=group,
                                group_x=None,
                                episode_offset=train,
                            )


# the designs `experiment.design` chooses from (conf/experiment/*.yaml), each a way of building the series
DESIGNS: Registry[Callable[[_Builder], None]] = Registry(
    "design",
    {
        name: getattr(_Builder, name)
        for name in ("round_robin", "benchmark", "self_play", "adaptation", "symmetry", "fidelity", "generalization")
    },
)


def read_series_index(run_dir: Path) -> list[SeriesSpec]:
    """The series of an experiment's run directory, from its experiment.json."""
    return [SeriesSpec.from_dict(s) for s in read_experiment(run_dir).series]


def find_checkpoint(run_dir: Path, scenario: str, red: str, blue: str, repetition: int, episode: int) -> Path:
    """The red checkpoint after `episode` of the series (scenario, red, blue, repetition) of another run."""
    for spec in read_series_index(run_dir):
        if (spec.scenario, spec.red, spec.blue, spec.repetition) == (
            scenario,
            red,
            blue,
            repetition,
        ) and spec.group is None:
            path = RunDir(RunDir(run_dir).series_dir(spec.id)).checkpoint(episode, "red")
            if has_team_state(path):
                return path.resolve()
            raise ConfigError(
                f"from_run: series {spec.id} of {run_dir} kept no checkpoint after episode {episode} "
                f"(expected {path}); run it with experiment.checkpoint_every or checkpoint_at"
            )
    raise ConfigError(f"from_run: {run_dir} has no series {scenario} {red} vs {blue} (repetition {repetition})")


def build_series(cfg: RunConfig, argv: list[str] | None = None) -> list[SeriesSpec]:
    """The series of the experiment selected in cfg.experiment (argv: the user's overrides)."""
    exp = cfg.experiment
    if exp is None:
        raise ConfigError("no experiment selected (experiment=NAME; see conf/experiment)")
    try:
        play = DESIGNS.find(exp.design)
    except ConfigError as exc:
        raise ConfigError(f"experiment {exp.name!r}: {exc}") from None
    builder = _Builder(cfg, exp, list(argv or []))
    play(builder)
    if not builder.series:
        raise ConfigError(f"experiment {exp.name!r} has no series (check scenarios/opponents)")
    return builder.series
