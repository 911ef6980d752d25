"""`pillagerbench <command> --help`: what the command does, its keys with their defaults and choices,
and examples, built when asked from the config files (conf/config.yaml and conf/llm/base.yaml: keys,
defaults and their comments), the schema (config/schema.py: the choices of a key), the registries
(scenarios, teams) and the config groups' folders (experiments, LLM presets). Each command's own
arguments (those that are not config keys) come from its docstring or its argparse parser.
HELP below only says which of these parts each command shows, and gives its examples.
"""

from __future__ import annotations

import contextlib
import importlib
import io
import re
import types
from dataclasses import dataclass
from importlib import resources
from typing import Any, Literal, Union, get_args, get_origin

from pydantic import BaseModel

ALL = "*"  # every key of conf/config.yaml


@dataclass(frozen=True)
class CommandHelp:
    usage: tuple[str, ...]
    examples: tuple[str, ...]
    keys: tuple[str, ...] = ()  # keys of conf/config.yaml (a section such as `server` stands for its keys)
    groups: tuple[str, ...] = ()  # config groups shown as keys: scenario, red, blue, llm, experiment, clock
    llm_keys: bool = False  # the keys of an LLM preset (conf/llm/base.yaml), as llm.KEY
    choices: tuple[str, ...] = ()  # lists to show: scenarios, teams, llm, experiments
    doc: bool = False  # the command's docstring (its own arguments)
    argparse: bool = False  # the command's argparse help (its arguments) instead of doc
    experiment: str | None = None  # the experiment it plays when none is chosen (its keys are shown)


GAME = ("episode_length", "seed", "display", "scoring", "protocol", "server", "llm_cache", "llm_ledger")
RUNNER = ("parallel", "launcher", "ray_address", "resume", "run_dir")

HELP: dict[str, CommandHelp] = {
    "run": CommandHelp(
        usage=(
            "pillagerbench run [key=value ...]",
            "pillagerbench run experiment=NAME [experiment.KEY=VALUE ...] [key=value ...]",
        ),
        keys=(ALL,),
        groups=("scenario", "red", "blue", "llm", "experiment", "clock"),
        llm_keys=True,
        choices=("scenarios", "teams", "llm", "experiments"),
        examples=(
            "pillagerbench run red=passive blue=balanced episodes=3",
            "pillagerbench run scenario=dash_and_dine red=cot blue=berries llm=openai llm.model=gpt-4o",
            "pillagerbench run experiment=main_benchmark experiment.team=cot llm=openai parallel=4",
        ),
    ),
    "setup": CommandHelp(
        usage=("pillagerbench setup [--watch]",),
        doc=True,
        examples=("pillagerbench setup", "pillagerbench setup --watch"),
    ),
    "server": CommandHelp(
        usage=("pillagerbench server [key=value ...]",),
        keys=("server", "watch"),
        doc=True,
        examples=(
            "pillagerbench server server.port=25565 server.operators=[Steve]",
            "pillagerbench server watch=8080",
        ),
    ),
    "try": CommandHelp(
        usage=("pillagerbench try scenario=NAME player=NAME code=FILE.js [key=value ...]",),
        doc=True,
        choices=("scenarios",),
        examples=(
            "pillagerbench try scenario=mushroom_war player=Ryn code=mine.js",
            "pillagerbench try scenario=mushroom_war player=Ryn code=- inventory='{\"bread\": 2}' full=true < mine.js",
        ),
    ),
    "llm-ping": CommandHelp(
        usage=("pillagerbench llm-ping [llm=PRESET] [llm.KEY=VALUE ...]",),
        groups=("llm",),
        llm_keys=True,
        choices=("llm",),
        examples=(
            "pillagerbench llm-ping llm=openai",
            "pillagerbench llm-ping llm=openai_compatible llm.base_url=http://127.0.0.1:8080/v1 llm.model=local",
        ),
    ),
    "compare": CommandHelp(
        usage=(
            "pillagerbench compare A B [opponent=O] [cap=PAIRS] [sprt.p0=P sprt.p1=P sprt.alpha=A sprt.beta=B] [key=value ...]",
            "pillagerbench compare resume=RUN_DIR",
        ),
        keys=GAME,
        groups=("scenario", "llm"),
        choices=("scenarios", "teams", "llm"),
        doc=True,
        examples=(
            "pillagerbench compare passive balanced opponent=do_nothing",
            "pillagerbench compare cot tacticrafter llm=openai llm.model=gpt-4o sprt.p1=0.7",
        ),
    ),
    "mcp": CommandHelp(
        usage=(
            "pillagerbench mcp [side=red] [opponent=NAME] [transport=stdio|http] [host=H] [port=P] [agent_model=M] [key=value ...]",
        ),
        keys=("episodes", "layout", "split", *GAME, "run_dir", "retries"),
        groups=("scenario", "clock"),
        choices=("scenarios", "teams"),
        doc=True,
        examples=(
            "pillagerbench mcp clock=lockstep episodes=3",
            "pillagerbench mcp side=blue opponent=balanced agent_model=gpt-4o transport=http port=8765",
        ),
    ),
    "teams": CommandHelp(
        usage=("pillagerbench teams",),
        doc=True,
        examples=("pillagerbench teams",),
    ),
    "league": CommandHelp(
        usage=("pillagerbench league LEAGUE_DIR {init|add|play|board} [KEY=VALUE ...]",),
        doc=True,
        choices=("scenarios", "teams", "llm"),
        examples=(
            "pillagerbench league leagues/mine add my_cot team=cot llm=openai llm.model=gpt-4o",
            "pillagerbench league leagues/mine play parallel=2",
            "pillagerbench league leagues/mine board",
        ),
    ),
    "replay": CommandHelp(
        usage=("pillagerbench replay RUN_DIR/episode_NNN",),
        doc=True,
        examples=("pillagerbench replay runs/2026-11-23_10-00-00_mushroom_war_passive_vs_balanced/episode_000",),
    ),
    "layout": CommandHelp(
        usage=(),
        argparse=True,
        examples=(
            "pillagerbench layout show mushroom_war 42",
            "pillagerbench layout show dash_and_dine paper --out map.html",
            "pillagerbench layout show mushroom_war 42 --json --out my_layout.json",
        ),
    ),
    "report": CommandHelp(
        usage=(),
        argparse=True,
        examples=(
            "pillagerbench report runs/RUN_A runs/RUN_B --out report",
            "pillagerbench report runs/RUN --calibration reference",
            "pillagerbench report runs/RUN --calibration runs/CALIBRATION_RUN/calibration.json",
        ),
    ),
    "symmetry": CommandHelp(
        usage=(),
        argparse=True,
        examples=("pillagerbench symmetry runs/SYMMETRY_RUN", "pillagerbench symmetry runs/ROUND_ROBIN_RUN"),
    ),
    "fidelity": CommandHelp(
        usage=(),
        argparse=True,
        examples=(
            "pillagerbench fidelity runs/FIDELITY_RUN",
            "pillagerbench fidelity runs/ROUND_ROBIN_RUN --calibration reference",
        ),
    ),
    "calibrate": CommandHelp(
        usage=("pillagerbench calibrate [key=value ...]", "pillagerbench calibrate RUN_DIR... [--out FILE]"),
        keys=GAME + RUNNER,
        doc=True,
        experiment="calibration",
        examples=(
            "pillagerbench calibrate parallel=4",
            "pillagerbench calibrate experiment.episodes=5 episode_length=60",
            "pillagerbench calibrate runs/ROUND_ROBIN_RUN --out calibration.json",
        ),
    ),
    "suite": CommandHelp(
        usage=(),
        argparse=True,
        examples=("pillagerbench suite", "pillagerbench suite --record 'suite 1.1'"),
    ),
    "export": CommandHelp(
        usage=(),
        argparse=True,
        examples=(
            "pillagerbench export runs/RUN --out results.tar.gz",
            "pillagerbench export runs/RUN_A runs/RUN_B --out results.tar.gz --replays",
        ),
    ),
    "verify": CommandHelp(usage=(), argparse=True, examples=("pillagerbench verify results.tar.gz",)),
}

# config groups as keys: what the key chooses (the options are listed under "choices")
GROUPS = {
    "scenario": ("scenario", "the scenario (see scenarios)"),
    "red": ("team@red", "the red team (see teams); its options: red.KEY=VALUE"),
    "blue": ("team@blue", "the blue team (see teams); its options: blue.KEY=VALUE"),
    "llm": ("llm", "the LLM preset (see LLM presets); its keys: llm.KEY=VALUE"),
    "experiment": (
        "experiment",
        "many series from the paper's experiment designs (see experiments); keys experiment.KEY",
    ),
    "clock": ("clock", "what game time is: real (the wall clock) or lockstep (docs/clock.md); keys clock.KEY"),
}


# --- The keys: conf/*.yaml read with their comments -----------------------------------------------------


def yaml_keys(text: str, prefix: str = "") -> list[tuple[str, str, str]]:
    """(dotted key, default as written, comment) for every leaf key of a YAML mapping, in order;
    a section (`server:`) lends its comment to keys that have none. The `defaults` list is left out."""
    out: list[tuple[str, str, str]] = []
    stack: list[tuple[int, str, str]] = []  # (indent, key, comment) of the open sections
    for line in text.splitlines():
        m = re.match(r"^(\s*)([A-Za-z_]\w*):(?:\s+(.*))?$", line)
        if not m:
            continue
        indent, key, rest = len(m.group(1)), m.group(2), m.group(3) or ""
        value, comment = ("", rest[1:]) if rest.startswith("#") else (re.split(r"\s+#\s?", rest, maxsplit=1) + [""])[:2]
        value, comment = value.strip(), comment.strip()
        while stack and stack[-1][0] >= indent:
            stack.pop()
        path = ".".join([prefix] * bool(prefix) + [k for _, k, _ in stack] + [key])
        if not value:  # a section (`defaults:` too: its items are `- ...` lines, never keys)
            stack.append((indent, key, comment))
            if comment:  # its comment speaks for its keys (theirs continue it): one line for all
                out.append((f"{path}.*", "", comment))
            continue
        section = next((i for i in range(len(out) - 1, -1, -1) if out[i][0] == f"{path.rpartition('.')[0]}.*"), None)
        if stack and stack[-1][2] and section is not None:
            if comment:
                out[section] = (out[section][0], "", f"{out[section][2]} {comment}")
            comment = ""
        out.append((path, value, comment))
    return out


def _conf(*parts: str) -> str:
    return (resources.files("pillagerbench.conf").joinpath(*parts)).read_text(encoding="utf-8")


def _literals(annotation: Any) -> list[str]:
    if get_origin(annotation) is Literal:
        return [str(a) for a in get_args(annotation)]
    if get_origin(annotation) in (Union, types.UnionType):
        return [x for a in get_args(annotation) for x in _literals(a)]
    return []


def schema_choices(model: type[BaseModel], path: list[str]) -> list[str]:
    """The choices of a key (a Literal in config/schema.py), or [] for a free value."""
    field = model.model_fields.get(path[0])
    if field is None:
        return []
    annotation = field.annotation
    if len(path) > 1:
        return (
            schema_choices(annotation, path[1:])
            if isinstance(annotation, type) and issubclass(annotation, BaseModel)
            else []
        )
    return _literals(annotation)


def _key_line(key: str, default: str, comment: str, choices: list[str]) -> str:
    if choices and not all(c in comment for c in choices):
        comment = f"{comment}; choices: {', '.join(choices)}" if comment else f"choices: {', '.join(choices)}"
    left = f"  {key}={default}" if default else f"  {key}"
    return f"{left:<36} {comment}".rstrip() if comment else left


def _group_defaults() -> dict[str, str]:
    from omegaconf import OmegaConf

    out = {}
    for d in OmegaConf.create(_conf("config.yaml")).defaults:
        if not isinstance(d, str):
            out.update({str(k): "null" if v is None else str(v) for k, v in d.items()})
    return out


def scenario_key_lines() -> list[str]:
    """The keys of the scenario group (conf/scenario/NAME.yaml but `name`): each with its value in
    every scenario, since that, not a top-level default, is what a match plays."""
    from pillagerbench.config.compose import config_options

    found: dict[str, tuple[list[str], str]] = {}
    for name in config_options("scenario"):
        for key, value, comment in yaml_keys(_conf("scenario", f"{name}.yaml"), "scenario"):
            if key != "scenario.name":
                values, first = found.setdefault(key, ([], comment))
                values.append(f"{name} {value}")
    return [
        _key_line(key, "", f"per scenario: {', '.join(values)}" + (f"; {comment}" if comment else ""), [])
        for key, (values, comment) in found.items()
    ]


def key_lines(spec: CommandHelp) -> list[str]:
    from pillagerbench.config.schema import LLMConfig, RunConfig

    lines = []
    chosen = _group_defaults()
    for group in spec.groups:
        hydra_name, what = GROUPS[group]
        lines.append(_key_line(group, chosen.get(hydra_name, "null"), what, []))
        if group == "scenario":
            lines += scenario_key_lines()
        if group == "clock":
            lines += [
                _key_line(key, default, comment, [])
                for key, default, comment in yaml_keys(_conf("clock", "lockstep.yaml"), "clock")
                if key != "clock.mode"
            ]
    for key, default, comment in yaml_keys(_conf("config.yaml")):
        if ALL in spec.keys or key in spec.keys or key.split(".")[0] in spec.keys:
            lines.append(_key_line(key, default, comment, schema_choices(RunConfig, key.split("."))))
    if spec.llm_keys:
        lines.append("")
        lines.append("llm.KEY (the chosen preset's settings, conf/llm/base.yaml; a preset changes some defaults):")
        for key, default, comment in yaml_keys(_conf("llm", "base.yaml")):
            lines.append(_key_line(f"llm.{key}", default, comment, schema_choices(LLMConfig, key.split("."))))
    return lines


# --- The choices: registries and config folders ---------------------------------------------------------


def _header(text: str) -> str:
    """The first sentence of a YAML file's leading comment."""
    lines = text.splitlines()
    block = lines[: next((i for i, line in enumerate(lines) if not line.startswith("#")), len(lines))]
    comment = " ".join(line.lstrip("# ").strip() for line in block)
    first = re.split(r"(?<=[\w)\]`'\"]\.)\s+(?=[A-Z])", comment, maxsplit=1)[0]
    return first if len(first) <= 110 else first[:109].rstrip() + "…"


def choice_lines(which: str) -> list[str]:
    from pillagerbench.config.compose import config_options

    if which == "scenarios":
        from pillagerbench.scenarios import SCENARIOS

        return ["scenarios (scenario=NAME):"] + [
            f"  {name:<26} {_header(_conf('scenario', f'{name}.yaml'))}" for name in SCENARIOS
        ]
    if which == "teams":
        from pillagerbench.teams.catalog import rows

        out = ["teams (red=NAME, blue=NAME; `pillagerbench teams` shows where each comes from):"]
        for r in rows():
            llm = ", uses an LLM" if r["llm"] == "yes" else ""
            options = f"; options {r['options']}" if r["options"] != "–" else ""
            out.append(f"  {r['team']:<26} scenarios: {r['scenarios']}{llm}{options}")
        return out + ["  package.module:Class       any Team subclass by import path (docs/your-team.md)"]
    if which == "llm":
        return ["LLM presets (llm=NAME):"] + [
            f"  {name:<26} {_header(_conf('llm', f'{name}.yaml'))}" for name in config_options("llm")
        ]
    if which == "experiments":
        return ["experiments (experiment=NAME; `pillagerbench run experiment=NAME --help` shows its keys):"] + [
            f"  {name:<26} {_header(_conf('experiment', f'{name}.yaml'))}" for name in config_options("experiment")
        ]
    raise ValueError(which)


def experiment_lines(name: str) -> list[str]:
    lines = [f"experiment.KEY (experiment={name}, conf/experiment/{name}.yaml):"]
    lines += [_key_line(k, v, c, []) for k, v, c in yaml_keys(_conf("experiment", f"{name}.yaml"), "experiment")]
    return lines


# --- One command's help ---------------------------------------------------------------------------------


def _function(target: str) -> Any:
    module_name, func_name = target.split(":")
    return getattr(importlib.import_module(module_name), func_name)


def _docstring(func: Any) -> str:
    """The command's own text: its function's docstring, or its module's for a `main`."""
    doc = func.__doc__ if func.__name__ != "main" else importlib.import_module(func.__module__).__doc__
    return (doc or "").strip("\n")


def argparse_help(func: Any) -> str:
    """The help of a command that parses its arguments with argparse (it exits after printing it)."""
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.suppress(SystemExit):
        func(["--help"])
    return out.getvalue().rstrip()


def _chosen_experiment(argv: list[str]) -> str | None:
    from pillagerbench.config.compose import config_options

    names = [v for k, sep, v in (a.partition("=") for a in argv) if sep and k == "experiment"]
    return names[-1] if names and names[-1] in config_options("experiment") else None


def command_help(name: str, command: tuple[str, str], argv: list[str] | None = None) -> str:
    """The help text of `pillagerbench NAME`; `command` is its entry of cli.COMMANDS ("module:function",
    summary); argv is the rest of the command line (`run experiment=X --help` adds X's keys)."""
    spec, func = HELP[name], _function(command[0])
    lines = [f"pillagerbench {name}: {command[1]}", ""]
    if spec.argparse:
        lines += [argparse_help(func)]
    else:
        lines += [f"usage: {spec.usage[0]}"] + [f"       {u}" for u in spec.usage[1:]]
        if spec.doc:
            lines += ["", _docstring(func)]
    keys = key_lines(spec) if spec.keys or spec.groups or spec.llm_keys else []
    if keys:
        lines += ["", "keys (key=value, no dashes; the default after =, from conf/config.yaml):", *keys]
    elif not spec.argparse and not any("=" in u for u in spec.usage):
        lines += ["", "keys: none"]
    experiment = _chosen_experiment(argv or []) if "experiments" in spec.choices else spec.experiment
    if experiment:
        lines += ["", *experiment_lines(experiment)]
    for which in spec.choices:
        lines += ["", *choice_lines(which)]
    lines += ["", "examples:", *(f"  {e}" for e in spec.examples)]
    return "\n".join(lines)


def version() -> str:
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as dist_version

    try:
        return dist_version("pillagerbench")
    except PackageNotFoundError:  # pragma: no cover - a source tree that was never installed
        return "unknown"
