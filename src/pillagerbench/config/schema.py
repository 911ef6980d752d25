"""The configuration's schema, and the configuration typed: `RunConfig` (every top-level key, the
groups `scenario`, `red`/`blue` and `llm`, each default written once, in conf/config.yaml, and taken
from there: `written(key)`) is what the command's edge
(cli, config/validate.py check_run_config) makes of the command line and conf/, and what every layer below
takes, whole or in part (RunnerConfig, TeamConfig, ServerConfig, LLMCacheConfig, LLMLedgerConfig).
`problems(model, data)` gives one line per problem, naming the key, the bad value and what is valid.
Groups (scenario, layout, teams) are checked against their registries by the checks match/validate.py
registers into config/validate.py, on the choices typed (`Choices`).
"""

from __future__ import annotations

import copy
import socket
from importlib import resources
from types import UnionType
from typing import Any, ClassVar, Final, Literal, Union, get_args, get_origin

from omegaconf import OmegaConf
from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    PrivateAttr,
    StrictInt,
    ValidationError,
    field_serializer,
    field_validator,
    model_validator,
)
from pydantic_core import PydanticCustomError

from pillagerbench.config.compose import ENV_NAME, ConfigError, looks_like_key, to_dict
from pillagerbench.config.game_tick import TICKS_PER_S
from pillagerbench.config.people import HUMAN_TEAM, SIDE_KEY, HumansConfig
from pillagerbench.config.sides import SIDES

SECRET = "secret"  # the error type of a value that must not be echoed (problems() names the key only)
# conf/config.yaml: every default of a key is written there, once (with the comment `run --help` shows;
# the suite's hash reads the rules' defaults there too); the models below take their defaults from it
CONF: dict[str, Any] = to_dict(OmegaConf.create((resources.files("pillagerbench.conf") / "config.yaml").read_text()))


def written(key: str) -> Any:
    """conf/config.yaml's default of a dotted key (`scoring`, `llm_cache.mode`)."""
    node: Any = CONF
    for part in key.split("."):
        node = node[part]
    return node


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")


class ServerConfig(_Strict):
    host: str
    port: int = Field(ge=0, le=65535)
    view_distance: int = Field(ge=1, le=32)
    crop_growth_chance: float = Field(ge=0, le=1)
    tps: float = Field(ge=1, le=200)
    operators: list[str]
    log_dir: str | None


class LLMCacheConfig(_Strict):
    mode: Literal["off", "read", "write", "readwrite", "replay"] = written("llm_cache.mode")
    dir: str | None = written("llm_cache.dir")


class LLMLedgerConfig(_Strict):
    content: Literal["full", "hash"] = written("llm_ledger.content")


class LLMConfig(_Strict):
    """The `llm` node (the fields of LLMSettings, with ranges)."""

    provider: str
    base_url: str
    model: str
    api_key_env: str | None
    temperature: float | None = Field(default=None, ge=0, le=2)
    max_tokens: int | None = Field(default=None, ge=1)
    timeout: float = Field(gt=0)
    max_retries: int = Field(ge=0)
    retry_backoff_s: float = Field(ge=0)
    retry_max_wait_s: float = Field(ge=0)
    system_role: Literal["system", "developer"]
    send_temperature: bool
    max_tokens_param: Literal["max_tokens", "max_completion_tokens"]
    strip_think: bool
    preflight: bool
    extra_headers: dict[str, str]
    extra_body: dict[str, Any]
    price: dict[Literal["input_per_1m", "output_per_1m"], float | None]
    budget: dict[Literal["max_calls", "max_input_tokens", "max_output_tokens", "max_cost_usd"], float | None]

    @field_validator("api_key_env")
    @classmethod
    def _a_variable_name(cls, value: str | None) -> str | None:
        """The NAME of the variable holding the key; a key here would be echoed and recorded."""
        if value is None or (ENV_NAME.fullmatch(value) and not looks_like_key(value)):
            return value
        what = "looks like a key, not" if looks_like_key(value) else "is not"
        raise PydanticCustomError(
            SECRET,
            f"{what} the name of an environment variable; put the key in a variable (export OPENAI_API_KEY=...) "
            "and give its name: llm.api_key_env=OPENAI_API_KEY",
        )


class _AsGiven(BaseModel):
    """A node typed, and kept as composed beside (`given()`: what the records write, numbers as written)."""

    _given: dict[str, Any] = PrivateAttr(default_factory=dict)

    @model_validator(mode="wrap")
    @classmethod
    def _as_composed(cls, data: Any, handler: Any) -> Any:
        model = handler(data)
        if isinstance(data, dict):
            model._given = copy.deepcopy(data)
        return model

    def given(self) -> dict[str, Any]:
        """The keys given, as composed (an empty node: none)."""
        return copy.deepcopy(self._given)


class LLMKeys(_AsGiven):
    """An `llm` node as composed: the run's (the preset) or a side's own keys (`red.llm.model=...`). Every
    key of LLMConfig, none required and no range checked here; the settings a side plays with (`llm_of`:
    the run's with the side's merged in) are checked whole by LLMConfig, and only for a side whose team uses
    an LLM (config/validate.py), so a run of two built-in teams is never refused for its unused preset. A
    key LLMConfig does not know is kept (refused there) so that an old run's stored config still reads;
    `given()` is the node as composed, its numbers as written (what the LLM layer reads, LLMSettings)."""

    model_config = ConfigDict(extra="allow", coerce_numbers_to_str=True)  # llm.model=7: the model '7'

    provider: str | None = None
    base_url: str | None = None
    model: str | None = None
    api_key_env: str | None = None
    temperature: float | None = None
    max_tokens: int | None = None
    timeout: float | None = None
    max_retries: int | None = None
    retry_backoff_s: float | None = None
    retry_max_wait_s: float | None = None
    system_role: str | None = None
    send_temperature: bool | None = None
    max_tokens_param: str | None = None
    strip_think: bool | None = None
    preflight: bool | None = None
    extra_headers: dict[str, Any] | None = None
    extra_body: dict[str, Any] | None = None
    price: dict[str, Any] | None = None
    budget: dict[str, Any] | None = None

    @classmethod
    def of(cls, data: Any, where: str = "llm") -> LLMKeys:
        """The typed node of `data` (a composed node or a mapping), or one ConfigError line per problem
        (each named under `where`)."""
        data = plain(data)
        check(problems(cls, data, where))
        return cls.model_validate(data)

    def over(self, own: LLMKeys) -> LLMKeys:
        """These keys with `own` merged in key by key (a side's over the run's)."""
        return LLMKeys.model_validate(merged(self._given, own._given))

    def problems(self, where: str) -> list[str]:
        """The problems of these keys as a side's whole LLM settings (LLMConfig), named under `where`."""
        return problems(LLMConfig, self._given, where)


RETRIES: int = written("retries")  # replays of a spoiled episode (rundir/schedule.py)


class ClockConfig(_Strict):
    """`clock=real|lockstep` (conf/clock/*.yaml): what game time is (docs/clock.md)."""

    mode: Literal["real", "lockstep"] = "real"
    speed: Literal["max"] | float = 1.0  # lockstep: a multiple of real time, or max (unpaced)
    ticks_per_1k_tokens: float | None = Field(default=None, ge=0)  # lockstep: game time charged for thinking

    @field_validator("speed", mode="before")
    @classmethod
    def _pace(cls, value: Any) -> Any:
        try:
            ok = value == "max" or (not isinstance(value, bool) and float(value) > 0)
        except (TypeError, ValueError):
            ok = False
        if not ok:
            raise PydanticCustomError(
                "clock_speed", "a multiple of real time above 0 (e.g. 1, 4), or max (as fast as the bots allow)"
            )
        return value


class ScenarioConfig(BaseModel):
    """The `scenario` node (conf/scenario/NAME.yaml); the name is checked against the registry (config/validate.py)."""

    model_config = ConfigDict(extra="ignore", coerce_numbers_to_str=True)  # scenario=5: unknown scenario, once

    name: str
    crop_growth_chance: float = Field(ge=0, le=1)  # what a match plays (server.crop_growth_chance is the start value)


class TeamConfig(BaseModel):
    """A side's node (`red`, `blue`): the team's name, its own `llm` keys, and its options (every other
    key, checked against the team's options model: config/validate.py)."""

    model_config = ConfigDict(extra="allow", coerce_numbers_to_str=True)  # red=7: unknown team '7', once

    name: str
    # keys of the run's `llm` this side plays with otherwise (red.llm.model=...)
    llm: LLMKeys = Field(default_factory=LLMKeys)

    @property
    def options(self) -> dict[str, Any]:
        """The team's constructor options: the node without `name`, `llm` and `humans` (config/people.py)."""
        return {k: v for k, v in (self.model_extra or {}).items() if k != SIDE_KEY}

    @property
    def humans(self) -> list[str]:
        """The side's players named by `red.humans=[Ryn]` (`red=human`: all of them, config/people.seats_of)."""
        return [str(n) for n in (self.model_extra or {}).get(SIDE_KEY) or []]


class Choices(BaseModel):
    """What a run chooses by name (the scenario and its layout, each side's team with its options and
    LLM), typed apart from the other keys so that the groups' checks (config/validate.py) run beside theirs."""

    model_config = ConfigDict(extra="ignore")

    scenario: ScenarioConfig
    red: TeamConfig
    blue: TeamConfig
    llm: LLMKeys
    layout: int | str = written("layout")
    split: str | None = written("split")
    clock: ClockConfig = ClockConfig()  # people play on the real clock only (config/people.py)

    def side(self, side: str) -> TeamConfig:
        """The team node of `red` or `blue`."""
        return {"red": self.red, "blue": self.blue}[side]

    def llm_of(self, side: str) -> LLMKeys:
        """The `llm` settings `side` plays with: the run's, with the side's own keys merged in."""
        return self.llm.over(self.side(side).llm)


class _Node(BaseModel):
    """A node of the experiment whose keys are fixed: a key it lacks or does not take is refused in one line
    naming the keys it takes (`WHAT takes ...`: problems())."""

    model_config = ConfigDict(extra="forbid", coerce_numbers_to_str=True)  # a team named 7: unknown team '7'

    WHAT: ClassVar[str]


class Variant(_Node):
    """One of an experiment's `variants` (its label the key): what it plays instead of the experiment's
    team, team options, LLM preset and LLM keys; a key not given is the experiment's (`over`)."""

    WHAT: ClassVar[str] = "a variant"

    team: str | None = None
    # the team's options: checked against the team's options model for each series (match/validate.py)
    team_options: dict[str, Any] | None = None
    llm: str | None = None  # an LLM preset; null = the run's llm=...
    llm_options: LLMKeys | None = None

    @model_validator(mode="before")
    @classmethod
    def _none_is_empty(cls, data: Any) -> Any:
        return {} if data is None else data  # `label:` with nothing after it: the experiment's team as it is

    def over(self, base: Variant) -> Variant:
        """This variant's keys given over `base` (the experiment's own team, options and LLM)."""
        return base.model_copy(update={key: getattr(self, key) for key in self.model_fields_set})


class Pairing(_Node):
    """One of the symmetry design's `pairings`: two teams, played in both orders in a scenario."""

    WHAT: ClassVar[str] = "a pairing"

    scenario: str = Field(min_length=1)
    a: str = Field(min_length=1)
    b: str = Field(min_length=1)


class ExperimentConfig(_AsGiven, _Node):
    """The `experiment` node (conf/experiment/NAME.yaml), each default written once, typed; kept as
    composed (`given()`: experiment.json and the manifest write that). What names a registry's entry (its
    design, teams, scenarios, the splits of `arenas`) is checked against it where the registry is known,
    experiments/spec.py, with the key the user set."""

    WHAT: ClassVar[str] = "an experiment"

    name: str
    design: str
    scenarios: list[str] = []
    episodes: int | None = Field(None, ge=0)  # per series (adaptation: train_episodes, generalization: arenas)
    repetitions: int | None = 1  # null or 0: once
    team: str | None = None
    # the team's options: checked against the team's options model for each series (match/validate.py)
    team_options: dict[str, Any] | None = None
    llm: str | None = None  # an LLM preset for the experiment's team; null = the run's llm=...
    llm_options: LLMKeys | None = None  # keys of that preset (or the run's llm) changed
    variants: dict[str, Variant] | None = None  # label -> what it changes of the team above
    opponents: list[str] | None = None  # null = the scenario's built-in opponents
    red_teams: list[str] | None = None
    blue_teams: list[str] | None = None
    pairings: list[Pairing] | None = None
    sides: list[Literal["blue", "red"]] | None = None
    arenas: dict[str, StrictInt] | None = None  # split -> episodes (splits: scenarios/layout.py SPLITS)
    checkpoint_every: int | None = None
    evaluate: bool = False
    train_episodes: int = 5
    from_run: str | None = None

    @model_validator(mode="before")
    @classmethod
    def _design_once_called_protocol(cls, data: Any) -> Any:
        """A node stored before the design had its own word called it `protocol` (an old manifest's; for
        experiment.json, rundir/experiment.py read_experiment); `given()` keeps it as stored."""
        if isinstance(data, dict) and "design" not in data and "protocol" in data:
            data = {("design" if key == "protocol" else key): value for key, value in data.items()}
        return data

    def own(self) -> Variant:
        """The experiment's own team, team options, LLM preset and LLM keys: what every variant changes."""
        return Variant(team=self.team, team_options=self.team_options or {}, llm=self.llm, llm_options=self.llm_options)


class RunnerConfig(BaseModel):
    """How an experiment's series are played, and where: every key its runner reads, declared once here.
    Each is the runner's alone (RUNNER_KEYS: a series' own config leaves it out, RunConfig.for_series)
    but `display`, which each series keeps, as each shows its own episodes."""

    model_config = ConfigDict(extra="ignore")

    parallel: int | None = Field(written("parallel"), ge=1)
    launcher: Literal["local", "ray"] = written("launcher")
    ray_address: str | None = written("ray_address")
    display: Literal["auto", "live", "plain"] = written("display")
    run_dir: str | None = written("run_dir")
    resume: str | None = written("resume")
    calibration: str | None = written("calibration")
    plan: bool = written("plan")
    experiment: ExperimentConfig | None = None  # the experiment design (experiments/spec.py builds its series)

    @field_serializer("experiment")
    def _experiment_as_given(self, experiment: ExperimentConfig | None) -> dict[str, Any] | None:
        return None if experiment is None else experiment.given()

    def stored(self) -> dict[str, Any]:
        """The configuration as a run directory stores it (an experiment's manifest.json): the keys given
        (a league round's runner keys and experiment, a compare's experiment alone), each as given."""
        return self.model_dump(exclude_unset=True)


# the keys of a run that are its runner's, not its series' (RunConfig.for_series leaves them out)
RUNNER_KEYS: Final = tuple(key for key in RunnerConfig.model_fields if key != "display")


class RunConfig(RunnerConfig):
    """The whole configuration, typed: the command line and conf/*.yaml composed (config.load_config),
    or a run's stored config (a manifest's, a series'). Every default is conf/config.yaml's (`written`:
    the schema writes none of its own, tests/test_config_schema.py); a stored config from before a key
    reads with it. `RunConfig.of(data)` builds it and keeps `data` as given
    (`stored()`): the records write that, numbers as they were composed."""

    server: ServerConfig
    llm_cache: LLMCacheConfig
    llm_ledger: LLMLedgerConfig
    episodes: int = Field(written("episodes"), ge=1)
    episode_length: float = Field(float(written("episode_length")), gt=0)  # seconds of game per episode
    seed: int = written("seed")
    scoring: Literal["clean", "upstream"] = written("scoring")
    protocol: Literal["pillagerbench", "upstream"] = written("protocol")
    paper: bool = written("paper")  # sets scoring and protocol to upstream's (config.compose.PAPER_SWITCHES)
    watch: int | None = Field(written("watch"), ge=0, le=65535)
    retries: int = Field(RETRIES, ge=0)
    outage_wait_s: float = Field(written("outage_wait_s"), ge=0, allow_inf_nan=False)  # experiments/outage.py
    layout: int | str = written("layout")  # checked in full by config/validate.layout_problems
    split: str | None = written("split")
    plan_width: float = Field(default=written("plan_width"), gt=0)
    plan_difference: float = Field(default=written("plan_difference"), gt=0)
    scenario: ScenarioConfig
    clock: ClockConfig = ClockConfig()
    humans: HumansConfig = HumansConfig.model_validate(written("humans"))  # people's page (config/people.py)
    red: TeamConfig
    blue: TeamConfig
    llm: LLMKeys  # the preset; checked per side that uses an LLM (config/validate.py, LLMConfig)

    _stored: dict[str, Any] = PrivateAttr(default_factory=dict)

    @classmethod
    def of(cls, data: Any) -> RunConfig:
        """The typed configuration of `data` (a composed DictConfig, or a stored dict)."""
        stored = plain(data)
        try:
            model = cls.model_validate(_normalised(stored))
        except ValidationError:  # a stored config that no longer reads: one line per problem
            check(problems(cls, _normalised(stored)))
            raise
        model._stored = stored
        return model

    def updated(self, changes: dict[str, Any]) -> RunConfig:
        """This configuration with `changes` merged in key by key (a series' seed, a variant's team
        options `{"red": {...}}` ...), typed again."""
        return RunConfig.of(merged(self._stored, changes))

    def with_llm(self, side: str, llm: LLMKeys) -> RunConfig:
        """This configuration with `side`'s own `llm` node replaced whole (a league entrant's LLM)."""
        stored = self.stored()
        stored[side] = {**stored[side], "llm": llm.given()}
        return RunConfig.of(stored)

    def stored(self) -> dict[str, Any]:
        """The configuration as composed or stored (what records write: manifest.json, experiment.json),
        every key, numbers as composed."""
        return copy.deepcopy(self._stored)

    def for_series(self) -> RunConfig:
        """A series' own configuration: this one without the runner's keys (RUNNER_KEYS), the one way they
        are left out (a plain run's, an experiment's series, a league's match, a resumed run's)."""
        return RunConfig.of({k: v for k, v in self._stored.items() if k not in RUNNER_KEYS})

    def select(self, key: str) -> Any:
        """A dotted key's value as stored (None if absent): conditions.conditions_of reads rules so."""
        node: Any = self._stored
        for part in key.split("."):
            if not isinstance(node, dict) or part not in node:
                return None
            node = node[part]
        return node

    def side(self, side: str) -> TeamConfig:
        """The team node of `red` or `blue`."""
        return {"red": self.red, "blue": self.blue}[side]

    def seated(self) -> list[str]:
        """The sides some of whose players people play (`red=human` or `red.humans=[...]`: config/people.py)."""
        return [side for side in SIDES if self.side(side).name == HUMAN_TEAM or self.side(side).humans]

    def llm_of(self, side: str) -> LLMKeys:
        """The `llm` settings `side` plays with: the run's, with the side's own keys merged in."""
        return self.llm.over(self.side(side).llm)

    def choices(self) -> Choices:
        """What this configuration chooses by name, as the groups' checks take it (config/validate.py)."""
        return Choices.model_validate(self._stored)


def default(key: str) -> Any:
    """The schema's default of a top-level key (`scoring`: "clean"): the one place it is written."""
    return RunConfig.model_fields[key].get_default(call_default_factory=True)


def plain(data: Any) -> dict[str, Any]:
    """`data` (a config node or a mapping) as a plain dict of its own (interpolations resolved)."""
    return to_dict(data) if OmegaConf.is_config(data) else copy.deepcopy(dict(data))


def _normalised(data: dict[str, Any]) -> dict[str, Any]:
    """YAML 1.1 reads a bare `off` as false: `llm_cache.mode=off` means "off"."""
    cache = data.get("llm_cache")
    if isinstance(cache, dict) and cache.get("mode") in (None, False):
        data = {**data, "llm_cache": {**cache, "mode": "off"}}
    return data


def merged(base: dict[str, Any], own: dict[str, Any]) -> dict[str, Any]:
    """`base` with `own` merged in, key by key down the nested mappings (as OmegaConf.merge)."""
    out = copy.deepcopy(base)
    for key, value in own.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = merged(out[key], value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def _where(prefix: str, loc: tuple) -> str:
    return ".".join([prefix, *map(str, loc)] if prefix else map(str, loc))


def _is_node(node: Any) -> bool:
    return isinstance(node, type) and issubclass(node, _Node)


def _bare(node: Any) -> Any:
    """`X | None`: X."""
    members = [a for a in get_args(node) if a is not type(None)] if get_origin(node) in (Union, UnionType) else []
    return members[0] if len(members) == 1 else node


def _holder(model: Any, loc: tuple) -> Any:
    """The type that holds the last key of an error's `loc` (a model, or None), down `model`'s fields,
    the values of its mappings and the items of its lists."""
    node = model
    for part in loc[:-1]:
        node = _bare(node)
        if isinstance(node, type) and issubclass(node, BaseModel):
            field = node.model_fields.get(str(part))
            node = field.annotation if field else None
        else:
            node = get_args(node)[-1] if get_origin(node) in (dict, list) else None
    return _bare(node)


def problems(model: type[BaseModel], data: Any, prefix: str = "") -> list[str]:
    """One line per problem of `data` (a dict or an OmegaConf node) against `model`."""
    if OmegaConf.is_config(data):
        data = OmegaConf.to_container(data, resolve=True)
    try:
        model.model_validate(data)
    except ValidationError as exc:
        out = []
        for e in exc.errors(include_url=False):
            key = _where(prefix, e["loc"])
            if e["type"] in ("extra_forbidden", "missing"):
                node = _holder(model, e["loc"])  # an experiment's node names the keys it takes
                takes = f" ({node.WHAT} takes {', '.join(node.model_fields)})" if _is_node(node) else ""
                out.append(f"{key}: {'unknown key' if e['type'] == 'extra_forbidden' else 'missing'}{takes}")
            elif e["type"] == SECRET:
                out.append(f"{key}: {e['msg']}")
            else:
                out.append(f"{key}={e.get('input')!r}: {e['msg'][0].lower() + e['msg'][1:]}")
        return out
    return []


def top_level_problems(cfg: Any) -> list[str]:
    """Problems of the top-level keys of a composed config (conf/config.yaml)."""
    return problems(RunConfig, _normalised(plain(cfg)))


def watch_problems(cfg: Any) -> list[str]:
    """`watch=PORT`: a port number, free on the server's host (0 = any free port)."""
    data = plain(cfg)
    watch = data.get("watch")
    if watch is None:
        return []
    if isinstance(watch, bool) or not isinstance(watch, int) or not 0 <= watch <= 65535:
        return [f"watch={watch!r}: a port number 0..65535 (0 = a free port), or null for no live view"]
    host = str((data.get("server") or {}).get("host", "127.0.0.1"))
    if watch and not port_is_free(host, watch):
        return [f"watch={watch}: port {host}:{watch} is already in use (choose another, or watch=0 for a free port)"]
    return []


def clock_problems(cfg: Any) -> list[str]:
    """What clock=lockstep cannot honour: a tick rate other than the game's (TICKS_PER_S, 20: its tick is 50 ms)."""
    data = plain(cfg)
    if (data.get("clock") or {}).get("mode") != "lockstep":
        return []
    tps = (data.get("server") or {}).get("tps", TICKS_PER_S)
    if tps != TICKS_PER_S:
        return [
            f"server.tps={tps}: clock=lockstep plays {TICKS_PER_S} ticks per game second (drop server.tps or clock=lockstep)"
        ]
    return []


def port_is_free(host: str, port: int) -> bool:
    with socket.socket(socket.AF_INET6 if ":" in host else socket.AF_INET, socket.SOCK_STREAM) as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            s.bind((host, port))
        except OSError:
            return False
    return True


def check(lines: list[str]) -> None:
    """Raise one ConfigError holding every line, if any."""
    if lines:
        raise ConfigError("\n".join(lines))
