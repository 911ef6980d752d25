"""The `pillagerbench` command: one sub-command per job, Hydra overrides after it."""

from __future__ import annotations

import importlib
import os
import sys
import time
import traceback
from pathlib import Path

# name -> ("module:function", help). Each function takes the remaining argv and returns an exit code.
COMMANDS: dict[str, tuple[str, str]] = {
    "run": ("pillagerbench.cli.commands:run_main", "play a match between two teams and record it"),
    "setup": ("pillagerbench.host.node:setup_main", "install the pinned Node packages into the cache"),
    "server": ("pillagerbench.server.serve:main", "start an arena server to watch with a 1.16.5 client"),
    "try": ("pillagerbench.players.try_code:main", "run a JavaScript file as one player and print its events"),
    "llm-ping": ("pillagerbench.llm.ping:main", "send one short request to an LLM provider"),
    "teams": ("pillagerbench.teams.catalog:main", "list every team: where it comes from, scenarios, LLM, options"),
    "league": (
        "pillagerbench.league.cli:main",
        "a league: add entrants, play scheduled matches, write the leaderboard",
    ),
    "replay": ("pillagerbench.replay.page:main", "write an episode's replay page (replay.html) from its recording"),
    "compare": (
        "pillagerbench.experiments.compare:main",
        "is entrant A better than B? paired play and a sequential test that stops when the answer is clear",
    ),
    "mcp": (
        "pillagerbench.mcp_front.play:main",
        "a run in which an MCP client plays a team through the game's tools (docs/any-agent.md)",
    ),
    "layout": ("pillagerbench.cli.layout_show:main", "show a layout's map (a page), or write the layout as JSON"),
    "report": ("pillagerbench.report.build:main", "tables, figures and an HTML page from run directories"),
    "symmetry": (
        "pillagerbench.report.symmetry:main",
        "each team's points as red and as blue per pairing (side effect check)",
    ),
    "fidelity": (
        "pillagerbench.report.fidelity:main",
        "built-in opponents vs do_nothing against upstream's scores, and the paper's claims on a round robin",
    ),
    "calibrate": (
        "pillagerbench.metrics.calibration:main",
        "σ_blue for the sabotage metric (runs or plays do_nothing vs every opponent)",
    ),
    "suite": (
        "pillagerbench.suite.version:main",
        "the suite version: its name and the hash of every file that can move a score",
    ),
    "export": (
        "pillagerbench.bundle.export:main",
        "one results bundle (an archive with checksums) from run directories",
    ),
    "verify": (
        "pillagerbench.bundle.verify:main",
        "check a results bundle: checksums, suite version, scores against their timelines",
    ),
}


def run_main(argv: list[str]) -> int:
    """`pillagerbench run`: one match (experiments/plain_run.py: a one-series experiment), or many
    series with experiment= (experiments/); resume= finishes either. The command line and conf/ are
    composed and checked here, once, into the typed configuration every layer below takes."""
    from pillagerbench.config.validate import load_run
    from pillagerbench.match import preflight  # the package registers the checks of the groups

    cfg = load_run(argv)  # the whole config, before anything is created
    if cfg.plan:  # what the run would play, take and cost; plays nothing (experiments/plan.py)
        from pillagerbench.experiments.plan import main_plan

        return main_plan(cfg, argv)
    if (
        cfg.experiment is not None or cfg.resume
    ):  # many series, parallel, resumable (they run the preflight on their series)
        from pillagerbench.experiments.runner import main_experiment

        return main_experiment(cfg, argv)
    from pillagerbench.experiments.plain_run import run_match

    preflight.check(preflight.sides_of(cfg))
    return run_match(cfg)


HELP_FLAGS = ("-h", "--help")


def usage() -> str:
    lines = ["usage: pillagerbench <command> [key=value ...]", "", "commands:"]
    lines += [f"  {name:<10} {help_}" for name, (_, help_) in COMMANDS.items()]
    lines += ["", "pillagerbench <command> --help: its keys, their defaults and choices, and examples", ""]
    lines += ["pillagerbench --version: the installed version and its suite version"]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv[:1] == ["help"] and argv[1:2] and argv[1] in COMMANDS:  # `help run` = `run --help`
        argv = [argv[1], "--help", *argv[2:]]
    if not argv or argv[0] in (*HELP_FLAGS, "help"):
        print(usage())
        return 0
    if argv[0] in ("-V", "--version"):
        from pillagerbench.cli.help import version
        from pillagerbench.suite.version import current

        print(f"pillagerbench {version()}\n{current()['name']} sha256:{current()['sha256']}")
        return 0
    name, rest = argv[0], argv[1:]
    if name not in COMMANDS:
        print(f"pillagerbench: unknown command {name!r}; valid commands: {', '.join(COMMANDS)}", file=sys.stderr)
        return 2
    if any(a in HELP_FLAGS for a in rest):  # help only: the command itself never starts
        from pillagerbench.cli.help import command_help

        try:
            print(command_help(name, COMMANDS[name], rest), flush=True)
        except BrokenPipeError:  # `... --help | head`: the reader has what it wanted
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    module_name, func_name = COMMANDS[name][0].split(":")
    try:
        func = getattr(importlib.import_module(module_name), func_name)
        return int(func(rest) or 0)
    except KeyboardInterrupt:
        return 130
    except Exception as exc:  # noqa: BLE001 - a user's error is one line; anything else is a bug of ours
        return _refuse(name, exc)


# The user's errors, by module and class, imported only once a command has run: an error of one of
# them can only come from a module that was imported, and the start of a light command (suite,
# layout, --version) does not pay for pandas, openai and Hydra.
CONFIG_ERRORS = (("pillagerbench.config.compose", "ConfigError"),)  # one line per problem, nothing started
USER_ERRORS = (
    ("pillagerbench.host.node", "NodeSetupError"),
    ("pillagerbench.metrics.runs", "ReportError"),
    ("pillagerbench.server.process", "ArenaServerError"),
    ("pillagerbench.config.args", "UsageError"),
    ("pillagerbench.rundir.bundle", "BundleError"),
    ("pillagerbench.experiments.series", "ResumeError"),
)
OS_ERRORS = (FileNotFoundError, PermissionError, IsADirectoryError)


def _loaded(errors: tuple[tuple[str, str], ...]) -> tuple[type, ...]:
    return tuple(getattr(sys.modules[module], cls) for module, cls in errors if module in sys.modules)


def _refuse(name: str, exc: Exception) -> int:
    """A user's error in one line (exit 2); a bug of ours in one line and a traceback file (exit 1)."""
    if isinstance(exc, _loaded(CONFIG_ERRORS)):
        for line in str(exc).splitlines() or [""]:
            print(f"pillagerbench {name}: {line}", file=sys.stderr)
        return 2
    if isinstance(exc, (*_loaded(USER_ERRORS), *OS_ERRORS)):
        print(f"pillagerbench {name}: {str(exc).splitlines()[0] if str(exc) else type(exc).__name__}", file=sys.stderr)
        return 2
    path = write_traceback(name)
    print(
        f"pillagerbench {name}: internal error: {type(exc).__name__}: {exc} (full traceback: {path}; please report it)",
        file=sys.stderr,
    )
    return 1


def write_traceback(command: str) -> Path:
    """The current exception's traceback in the cache's errors/ folder; returns its path."""
    from pillagerbench.host.node import cache_root

    folder = cache_root() / "errors"
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{time.strftime('%Y-%m-%d_%H-%M-%S')}_{command}.txt"
    path.write_text(traceback.format_exc())
    return path


if __name__ == "__main__":
    sys.exit(main())
