"""league.yaml: the entrants, scenarios, episodes per match, budget and confidence of a league.

    scenarios: [mushroom_war]
    episodes_per_match: 2       # episodes of one scheduled match (one series)
    matches_per_round: 2        # matches scheduled at once (played in parallel)
    confidence: 0.95            # adjacent entrants are separated when P(higher > lower) >= this
    margin: 0.0                 # openskill margin: > 0 lets the points difference weigh an update
    budget: {episodes: 400, hours: null, llm_tokens: null, llm_cost_usd: null}
    entrants:
      - {name: do_nothing, team: do_nothing, options: {}, llm: null, llm_options: {}}

    mix_suites: false           # true: rate rounds of different suite versions together (the board says so)
    no_verify: false            # true: read handed-over bundles that fail their checks (the board says so)
    split: paper                # the layouts rated on: paper, test (a fresh layout every episode) or dev

`play` and `board` may override any of these keys for one invocation (`budget.episodes=4`, `scenarios=[...]`,
`mix_suites=true`, `no_verify=true`, `split=test`).
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import yaml  # type: ignore[import-untyped]  # pyyaml ships no stubs

from pillagerbench.config.compose import ConfigError
from pillagerbench.league.splits import check_split

LEAGUE_FILE = "league.yaml"
BUDGET_KEYS = ("episodes", "hours", "llm_tokens", "llm_cost_usd")
DEFAULT_SCENARIOS = ["mushroom_war"]
OLD_STAMP = 16  # the length of an entrant's identity in a round's league.json before the entrant type


@dataclass
class RosterEntry:
    """One entrant of the roster as league.yaml writes it: its name in the league, its team, options and
    LLM (a preset and options). Its identity is the entrant it plays as (rundir/entrant.py), computed from
    the config the league composes for it (league/compose.py `entrant_of_entry`)."""

    name: str
    team: str
    options: dict[str, Any] = field(default_factory=dict)
    llm: str | None = None  # an llm preset (conf/llm/NAME.yaml)
    llm_options: dict[str, Any] = field(default_factory=dict)

    def old_fingerprint(self) -> str:
        """The identity league.json stamped before the entrant type (16 hex digits of league.yaml's
        entry without its name); only read to check the stamps of rounds played then (league/rounds.py)."""
        d = asdict(self)
        d.pop("name")
        return hashlib.sha256(json.dumps(d, sort_keys=True, default=str).encode()).hexdigest()[:OLD_STAMP]


@dataclass
class League:
    scenarios: list[str] = field(default_factory=lambda: list(DEFAULT_SCENARIOS))
    episodes_per_match: int = 2
    matches_per_round: int = 2
    confidence: float = 0.95
    margin: float = 0.0
    budget: dict[str, float | None] = field(
        default_factory=lambda: {"episodes": 400.0} | dict.fromkeys(BUDGET_KEYS[1:])
    )
    entrants: list[RosterEntry] = field(default_factory=list)
    mix_suites: bool = False  # rate episodes of different suite versions together (the board says so)
    no_verify: bool = False  # read handed-over bundles (matches/*.tar.gz) that fail their checks (the board says so)
    split: str = "paper"  # the layouts its matches are played and rated on (league/splits.py)

    def entrant(self, name: str) -> RosterEntry | None:
        return next((e for e in self.entrants if e.name == name), None)

    def to_dict(self) -> dict:
        return asdict(self)


def _checked(raw: dict, where: str) -> League:
    if not isinstance(raw, dict):
        raise ConfigError(f"{where}: not a mapping of league keys")
    unknown = sorted(set(raw) - set(League.__dataclass_fields__))
    if unknown:
        raise ConfigError(f"{where}: unknown key {unknown[0]!r}; valid: {', '.join(League.__dataclass_fields__)}")
    try:
        entrants = [RosterEntry(**e) for e in raw.get("entrants") or []]
        league = League(**{**raw, "entrants": entrants})
        budget = {k: None for k in BUDGET_KEYS} | dict(league.budget or {})
        bad = sorted(set(budget) - set(BUDGET_KEYS))
        if bad:
            raise ConfigError(f"{where}: unknown budget key {bad[0]!r}; valid: {', '.join(BUDGET_KEYS)}")
        league.budget = {k: (None if v is None else float(v)) for k, v in budget.items()}
        league.episodes_per_match, league.matches_per_round = (
            int(league.episodes_per_match),
            int(league.matches_per_round),
        )
        league.confidence, league.margin = float(league.confidence), float(league.margin)
        league.scenarios = [str(s) for s in league.scenarios]
    except (TypeError, ValueError) as exc:
        raise ConfigError(f"{where}: {exc}") from None
    league.split = check_split(league.split, where)
    if not 0.5 < league.confidence < 1:
        raise ConfigError(f"{where}: confidence={league.confidence} must be between 0.5 and 1")
    if league.episodes_per_match < 1 or league.matches_per_round < 1:
        raise ConfigError(f"{where}: episodes_per_match and matches_per_round must be at least 1")
    names = [e.name for e in league.entrants]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise ConfigError(f"{where}: two entrants are named {twice[0]!r}; entrant names must be unique")
    return league


def league_path(league_dir: Path) -> Path:
    return Path(league_dir) / LEAGUE_FILE


def load_league(league_dir: Path) -> League:
    path = league_path(league_dir)
    if not path.exists():
        raise ConfigError(f"{league_dir}: no {LEAGUE_FILE} (create it with `pillagerbench league {league_dir} init`)")
    try:
        raw = yaml.safe_load(path.read_text()) or {}
    except yaml.YAMLError as exc:
        raise ConfigError(f"{path}: not YAML: {str(exc).splitlines()[0]}") from None
    return _checked(raw, str(path))


def save_league(league_dir: Path, league: League) -> None:
    path = league_path(league_dir)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp")
    tmp.write_text(yaml.safe_dump(league.to_dict(), sort_keys=False))
    tmp.replace(path)


def parse_value(text: str) -> Any:
    """A command-line value as YAML (`2`, `0.9`, `[a,b]`, `true`, `null`, or a string)."""
    try:
        return yaml.safe_load(text)
    except yaml.YAMLError:
        return text


def with_overrides(league: League, overrides: dict[str, Any]) -> League:
    """The league with `key=value` / `budget.key=value` overrides applied (checked like the file)."""
    raw = league.to_dict()
    raw["entrants"] = [asdict(e) for e in league.entrants]
    for key, value in overrides.items():
        head, _, sub = key.partition(".")
        if head == "budget" and sub:
            raw["budget"] = dict(raw["budget"]) | {sub: value}
        else:
            raw[key] = value
    return _checked(raw, "league overrides")
