"""Hydra configuration: `pillagerbench <command> key=value group=option ...`.

Configs live in `pillagerbench/conf` (groups: `llm`, later `scenario`, `team`, `experiment`).
We use Hydra's compose API so every sub-command takes the same override syntax.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from typing import Any

from hydra import compose, initialize_config_module
from hydra.core.global_hydra import GlobalHydra
from hydra.errors import HydraException
from omegaconf import DictConfig, OmegaConf

from pillagerbench.config.people import SIDE_KEY


class ConfigError(ValueError):
    """Bad configuration or override; the message names the problem and the valid choices."""


def unknown(kind: str, name: object, known: Iterable[str], hint: str = "") -> ConfigError:
    """The one form of every unknown-name error, whatever the kind (a team, a scenario, a scoring, a
    design, an llm preset, a split ...): `unknown team 'cott'; known: aggressive, balanced, ...`."""
    return ConfigError(f"unknown {kind} {name!r}; known: {', '.join(known)}{f' {hint}' if hint else ''}")


# `red=cot` chooses an option of the `team` group for the red side (Hydra spells it `team@red=cot`);
# `red.llm.model=...` still sets a key inside it.
GROUP_ALIASES = {"red": "team@red", "blue": "team@blue"}


OPEN_KEYS = ("experiment.team_options.", "experiment.llm_options.")
EXTERNAL = "_external"  # conf/team/_external.yaml: teams without a YAML file of their own


def team_yaml_options(name: str) -> dict[str, Any] | None:
    """The options (with their defaults, without name and llm) of `conf/team/<name>.yaml`, or None
    for a team without a YAML file of its own."""
    from importlib import resources

    path = resources.files("pillagerbench.conf") / "team" / f"{name}.yaml"
    if not path.is_file():
        return None
    data = to_dict(OmegaConf.create(path.read_text()))
    return {k: v for k, v in data.items() if k not in ("name", "llm", "defaults")}


def _has_yaml(team: str) -> bool:
    return team_yaml_options(team) is not None


def _aliases(overrides: list[str]) -> list[str]:
    """Our spellings in Hydra's: `red=X` is `team@red=X`; a team without a YAML file of its own
    (import path, entry point, remote) is `team@red=_external` plus `red.name=X`, and its options
    `red.KEY=V` are added keys; a side's `llm.*` keys and `humans` (config/people.py) may be new too."""
    side_of = {v: k for k, v in GROUP_ALIASES.items()}
    chosen = {
        side_of.get(k, k): v
        for k, sep, v in (o.partition("=") for o in overrides)
        if sep and side_of.get(k, k) in GROUP_ALIASES
    }
    external = {side for side, team in chosen.items() if not _has_yaml(team)}
    out = []
    for override in overrides:
        key, sep, value = override.partition("=")
        group = side_of.get(key, key)
        if sep and group in GROUP_ALIASES:
            if value != chosen[group]:
                continue  # a later choice for this side wins
            out += (
                [f"{GROUP_ALIASES[group]}={EXTERNAL}", f"++{group}.name={value}"]
                if group in external
                else [f"{GROUP_ALIASES[group]}={value}"]
            )
            continue
        if sep and key.startswith(OPEN_KEYS):  # maps whose keys the user chooses
            out.append(f"++{override}")
            continue
        side, _, rest = key.partition(".")
        if sep and side in GROUP_ALIASES and (rest.startswith("llm.") or rest == SIDE_KEY or side in external):
            out.append(f"++{override}")
            continue
        out.append(override)
    return out


GROUP_WORDS = {"team": "team", "scenario": "scenario", "experiment": "experiment", "llm": "llm preset"}


def _team_keys(side: str, overrides: list[str]) -> str:
    """The keys of the team chosen for `side` (from the overrides, else the default), for a message."""
    from importlib import resources

    root = resources.files("pillagerbench.conf")
    defaults = OmegaConf.create((root / "config.yaml").read_text()).defaults
    name = next(
        d[f"team@{side}"] for d in defaults if isinstance(d, dict) or OmegaConf.is_dict(d) if f"team@{side}" in d
    )
    for o in overrides:
        key, _, value = o.partition("=")
        if key in (side, f"team@{side}"):
            name = value
    keys = list(team_yaml_options(name) or {})
    return f"team {name} has {'options ' + ', '.join(keys) if keys else 'no options'}"


ENV_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_KEY_PREFIX = re.compile(r"(sk|rk|pk|gsk|hf|ghp|xai|key)[-_]", re.I)


def looks_like_key(value: str) -> bool:
    """An API key, not a name: a provider's key prefix (sk-, gsk_, hf_, ...) or a long run of
    letters and digits with both cases or digits (environment variable names are short words)."""
    value = str(value)
    if _KEY_PREFIX.match(value):
        return True
    return (
        len(value) >= 24
        and re.fullmatch(r"[A-Za-z0-9_\-.]+", value) is not None
        and bool(re.search(r"\d", value))
        and bool(re.search(r"[a-z]", value))
    )


def _masked(text: str, overrides: list[str]) -> str:
    """`text` without any value of `overrides` that looks like a key."""
    for o in overrides:
        value = o.partition("=")[2]
        if value and looks_like_key(value):
            text = text.replace(value, "***")
    return text


def flag_problem(overrides: list[str]) -> str | None:
    """`--episodes 3` / `--episodes=3`: this command takes key=value; the message shows how."""
    for i, o in enumerate(overrides):
        if not o.startswith("-") or o in ("-", "--"):
            continue
        key, sep, value = o.lstrip("-").partition("=")
        following = overrides[i + 1] if i + 1 < len(overrides) else ""
        given = o
        if not sep and following and "=" not in following and not following.startswith("-"):
            given, value = f"{o} {following}", following
        if value and looks_like_key(value):  # never echo a key
            given, value = given.replace(value, "..."), "..."
        return f"{given}: write {key}={value or 'VALUE'} (options are key=value, without dashes; --help lists the keys)"
    return None


def _experiment_chosen(overrides: list[str]) -> str | None:
    chosen = [v for k, sep, v in (o.partition("=") for o in overrides) if sep and k.lstrip("+~") == "experiment"]
    return chosen[-1] if chosen and chosen[-1] not in ("null", "") else None


def _no_such_key(key: str, overrides: list[str]) -> str:
    if ENV_NAME.fullmatch(key) and key.isupper():  # OPENAI_API_KEY=...: an environment variable, not a key
        return (
            f"{key}: no such key; it looks like an environment variable: set it in the shell, not here "
            f"(export {key}=...), and name it with llm.api_key_env={key} if the preset does not already"
        )
    if key.startswith("experiment.") and not _experiment_chosen(overrides):
        return (
            f"{key}: no such key: no experiment is chosen; choose one first with experiment=NAME "
            f"(valid: {', '.join(config_options('experiment'))})"
        )
    experiment = _experiment_chosen(overrides)
    if key.startswith("experiment.") and experiment in config_options("experiment"):
        from importlib import resources

        text = (resources.files("pillagerbench.conf") / "experiment" / f"{experiment}.yaml").read_text()
        experiment_cfg = OmegaConf.create(text)
        node, path = experiment_cfg, ["experiment"]
        for part in key.split(".")[1:]:  # down to the deepest key the experiment has
            if not isinstance(node, DictConfig) or part not in node:
                break
            node, path = node[part], [*path, part]
        if len(path) > 1 and isinstance(node, DictConfig) and len(node):  # a table, given a key it lacks
            where = ".".join(path)
            what = "the value names a key it does not take" if where == key else "no such key"
            return f"{key}: {what} ({where} takes {', '.join(map(str, node))})"
        keys = [str(k) for k in experiment_cfg if k != "defaults"]
        return f"{key}: no such key (experiment {experiment} has keys {', '.join(keys)})"
    return f"{key}: no such key (conf/config.yaml lists the top-level keys; --help lists them all)"


def config_options(group: str) -> list[str]:
    """The options of a config group: the YAML files of `conf/<group>/` (without `base` and `_*`)."""
    from importlib import resources

    folder = resources.files("pillagerbench.conf") / group
    names = [p.name.removesuffix(".yaml") for p in folder.iterdir() if p.name.endswith(".yaml")]
    return sorted(n for n in names if n != "base" and not n.startswith("_"))


def one_line(message: str, overrides: list[str] | None = None) -> str:
    """Hydra's message without its config search path, on one line, in our words."""
    missing = re.search(r"Could not find '(\w+)/([^']*)'", message)
    if missing:
        group, name = missing.groups()
        options = re.findall(r"^\t(\S+)$", message, flags=re.M)
        options = [o for o in options if o != "base"] if group == "llm" else options
        return str(unknown(GROUP_WORDS.get(group, group), name, options))
    override = re.search(r"Could not override '([^']+)'", message)
    if override:
        key = override.group(1)
        side = key.split(".")[0]
        if side in GROUP_ALIASES:
            return f"{key}: no such option ({_team_keys(side, overrides or [])})"
        return _no_such_key(key, overrides or [])

    first = message.strip().splitlines()[0] if message.strip() else message
    return _masked(f"bad override: {first}", overrides or [])


def load_config(overrides: list[str] | None = None, config_name: str = "config") -> DictConfig:
    flag = flag_problem(list(overrides or []))
    if flag:
        raise ConfigError(flag)
    GlobalHydra.instance().clear()
    try:
        with initialize_config_module(config_module="pillagerbench.conf", version_base="1.3"):
            cfg = compose(config_name=config_name, overrides=_aliases(list(overrides or [])))
    except HydraException as exc:  # unknown group option, bad override syntax, ...
        raise ConfigError(one_line(str(exc), list(overrides or []))) from None
    OmegaConf.set_readonly(cfg, False)
    _apply_paper(cfg, list(overrides or []))
    _apply_answer_cap(cfg, list(overrides or []))
    return cfg


# paper=true: the settings the paper's tables were measured with, upstream's scoring and upstream's
# step protocol (docs/faithful.md says what each reproduces). A run that asks for it and sets one of
# them otherwise is refused rather than half comparable.
PAPER_SWITCHES = {"scoring": "upstream", "protocol": "upstream"}


def _apply_paper(cfg: DictConfig, overrides: list[str]) -> None:
    if OmegaConf.select(cfg, "paper") is not True:
        return
    if (clock := OmegaConf.select(cfg, "clock.mode")) not in (None, "real"):
        raise ConfigError(
            f"paper=true plays on the real clock (as the paper's episodes); drop clock={clock} or paper=true"
        )
    for key, value in PAPER_SWITCHES.items():
        given = [v for k, sep, v in (o.partition("=") for o in overrides) if sep and k.lstrip("+~") == key]
        if given and given[-1] != value:
            raise ConfigError(
                f"paper=true plays with {key}={value} (as the paper's tables); drop {key}={given[-1]} or paper=true"
            )
        cfg[key] = value


def _apply_answer_cap(cfg: DictConfig, overrides: list[str]) -> None:
    """`llm.max_tokens=N` (or `<side>.llm.max_tokens=N`) given on the command line caps every answer of
    that side: a team's own cap (cot's 4096, tools' 2048: `<side>.max_tokens`) larger than N becomes N,
    the stricter limit winning, so the user's limit applies. A preset's own max_tokens does not."""
    given = {k.lstrip("+~"): v for k, sep, v in (o.partition("=") for o in overrides) if sep}
    for side in GROUP_ALIASES:
        node = OmegaConf.select(cfg, side)
        if not OmegaConf.is_dict(node) or node.get("max_tokens") is None:
            continue
        asked = given.get(f"{side}.llm.max_tokens", given.get("llm.max_tokens"))
        if asked is None or not asked.isdigit():
            continue  # none given (a bad value is the schema's to refuse)
        node["max_tokens"] = min(int(node["max_tokens"]), int(asked))


def to_dict(cfg: Any) -> dict[str, Any]:
    """A config node (a mapping) as plain Python data, interpolations resolved."""
    data = OmegaConf.to_container(cfg, resolve=True)
    if not isinstance(data, dict):
        raise ConfigError(f"expected a mapping, got {type(data).__name__}: {data!r}")
    return {str(k): v for k, v in data.items()}
