"""The conditions of play: every configuration key, declared once as moving a score or not.

A score names the rules that made it. The suite version (suite/version.py) hashes the files that can move a
score; this table declares the *settings* that can: each key of the configuration is here, either as a
`RULE` (a setting of the whole run that changes the game: the tick rate, the episode's length, the
scoring, the step protocol, crop growth, what a bot can see), as an `ARENA` setting (the layout of each
episode: recorded on every episode as `layout` and `split`, and compared by split wherever layouts
differ), or as one that moves no score (`NOT`, with why). `tests/test_conditions.py` fails for a key
of any configuration that is in none of them, so a new setting cannot move scores unnoticed.

A run whose `RULE`s differ from the suite's defaults (conf/config.yaml and conf/scenario/*.yaml, whose
values of these keys the suite hash covers) records the differing keys and values on every episode
(`conditions`), and its stamp says so: `suite 1.0@a5ec7633b825fbba [episode_length=30]`. Readers put
episodes of one stamp in a table and refuse to mix stamps unless asked (metrics/runs.py).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any, Literal

Kind = Literal["rule", "arena", "not"]
RULE: Kind = "rule"
ARENA: Kind = "arena"
NOT: Kind = "not"


@dataclass(frozen=True)
class Setting:
    """A configuration key (dotted; a key ending in `.*` stands for its whole subtree) and whether it can
    move a score."""

    key: str
    kind: Kind
    why: str


SETTINGS: tuple[Setting, ...] = (
    # -- rules: stamped on every episode when they differ from the suite's defaults
    Setting("server.tps", RULE, "the game's speed: physics, digging, furnaces, growth and egg farms follow it"),
    Setting("server.view_distance", RULE, "the chunks a bot has loaded: what it can find and see"),
    Setting("scenario.crop_growth_chance", RULE, "a fixed growth chance per crop and second instead of vanilla's"),
    Setting("episode_length", RULE, "the seconds of play: every score is the score at the whistle"),
    Setting("scoring", RULE, "which score red_score/blue_score are: clean or upstream's quirks"),
    Setting("protocol", RULE, "the step loop: upstream's waits around every run (built-in opponents too)"),
    Setting(
        "clock.mode", RULE, "what game time is: the wall clock (load and LLM latency cost game time) or lockstep ticks"
    ),
    Setting("clock.ticks_per_1k_tokens", RULE, "lockstep: the game time a team's thinking costs"),
    Setting(
        "humans.client", RULE, "what people play with: the page (its controls, primitive buttons) or a Minecraft client"
    ),
    # -- arena: recorded on every episode (layout, split); tables and references compare by split
    Setting("layout", ARENA, "where everything is in the arena (recorded per episode as layout)"),
    Setting("split", ARENA, "each episode on its own generated layout (recorded per episode as split)"),
    # -- the entrant's (a team with its models and options: recorded with the team), not the rules'
    Setting("red.*", NOT, "the red entrant (its team, options and models are recorded with it)"),
    Setting("blue.*", NOT, "the blue entrant (its team, options and models are recorded with it)"),
    Setting("llm.*", NOT, "the LLM teams' provider and model: part of the entrant"),
    Setting("llm_cache.*", NOT, "where answers come from; every answer is in the ledger"),
    Setting("llm_ledger.*", NOT, "what the ledger keeps of each call"),
    Setting("experiment.*", NOT, "the experiment's design: each series' own config holds its settings"),
    # -- moves no score
    Setting("scenario.name", NOT, "the scenario itself: every table is per scenario"),
    Setting("server.host", NOT, "where the server listens"),
    Setting("server.port", NOT, "where the server listens"),
    Setting("server.crop_growth_chance", NOT, "the server's start value; every match sets its scenario's"),
    Setting("server.operators", NOT, "people watching may use commands; agents never can"),
    Setting("server.log_dir", NOT, "where the server's log goes"),
    Setting("episodes", NOT, "how many episodes, not how they are played"),
    Setting("seed", NOT, "a sample of the same conditions (recorded on every episode)"),
    Setting("paper", NOT, "sets scoring=upstream protocol=upstream, which are rules"),
    Setting("run_dir", NOT, "where the run is written"),
    Setting("display", NOT, "how the terminal shows the run"),
    Setting("watch", NOT, "the live view (bounded so it never holds the game up)"),
    Setting("humans.port", NOT, "where the people's page listens"),
    Setting("humans.ready_timeout_s", NOT, "how long the match waits for people before it plays"),
    Setting("clock.speed", NOT, "lockstep: how fast game time passes on the wall, not what happens in it"),
    Setting("parallel", NOT, "matches at once: load is recorded per episode as lag"),
    Setting("launcher", NOT, "where series run: load is recorded per episode as lag"),
    Setting("ray_address", NOT, "where series run"),
    Setting("resume", NOT, "finishing a killed run with the same settings"),
    Setting("calibration", NOT, "σ_blue for the sabotage metric; the report names the calibration it used"),
    Setting("plan", NOT, "prints the plan; plays nothing"),
    Setting("plan_width", NOT, "a question the plan answers; plays nothing"),
    Setting("plan_difference", NOT, "a question the plan answers; plays nothing"),
    Setting("retries", NOT, "how often an episode spoiled on our side is played again (it is in no score)"),
    Setting(
        "outage_wait_s",
        NOT,
        "how long a series waits for a provider or team server that stopped answering; it plays nothing meanwhile",
    ),
)
RULES: tuple[str, ...] = tuple(s.key for s in SETTINGS if s.kind == RULE)

CONF = Path(__file__).resolve().parents[1] / "conf"


def setting_of(key: str) -> Setting | None:
    """The declared setting a dotted key falls under (itself, or a `.*` subtree), None when undeclared."""
    for s in SETTINGS:
        if key == s.key or (s.key.endswith(".*") and key.startswith(s.key[:-1])):
            return s
    return None


def _select(tree: Mapping[str, Any], key: str) -> Any:
    node: Any = tree
    for part in key.split("."):
        if not isinstance(node, Mapping) or part not in node:
            return None
        node = node[part]
    return node


def defaults_from(conf: Path) -> dict[str, dict[str, Any]]:
    """The suite's default of every rule, per scenario: conf/config.yaml with conf/scenario/NAME.yaml
    as `scenario` ({scenario: {key: value}})."""
    import yaml  # type: ignore[import-untyped]

    top = yaml.safe_load((conf / "config.yaml").read_text()) or {}
    top["clock"] = yaml.safe_load((conf / "clock" / f"{DEFAULT_CLOCK}.yaml").read_text()) or {}
    out = {ANY_SCENARIO: {key: _select(top, key) for key in RULES}}  # a scenario of no conf/scenario file
    for path in sorted((conf / "scenario").glob("*.yaml")):
        tree = {**top, "scenario": yaml.safe_load(path.read_text()) or {}}
        out[path.stem] = {key: _select(tree, key) for key in RULES}
    return out


ANY_SCENARIO = "*"
DEFAULT_CLOCK = "real"  # conf/config.yaml's defaults list: clock: real


@lru_cache(maxsize=1)
def _defaults() -> dict[str, dict[str, Any]]:
    return defaults_from(CONF)


def suite_defaults(scenario: str) -> dict[str, Any]:
    """The suite's default of every rule in `scenario` (conf/config.yaml's alone for an unknown one)."""
    found = _defaults()
    return found.get(scenario, found[ANY_SCENARIO])


def conditions_of(select: Callable[[str], Any], scenario: str) -> dict[str, Any]:
    """The rules a run plays under that differ from the suite's defaults ({} = the suite's own),
    `select(key)` reading a dotted key of its configuration."""
    defaults = suite_defaults(scenario)
    out = {}
    for key in RULES:
        value = select(key)
        if key in defaults and value != defaults[key]:
            out[key] = value
    return out


def describe(conditions: Mapping[str, Any]) -> str:
    """`key=value, ...` in key order ('' for the suite's own conditions)."""
    return ", ".join(f"{k}={v}" for k, v in sorted(conditions.items()))


def stamp(suite_label: str, conditions: Mapping[str, Any]) -> str:
    """The suite and the conditions an episode was played under: `suite 1.0@H` or `suite 1.0@H [k=v, ...]`."""
    return f"{suite_label} [{describe(conditions)}]" if conditions else suite_label
