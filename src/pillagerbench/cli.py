"""The `pillagerbench` command: one sub-command per job, Hydra overrides after it."""

from __future__ import annotations

import importlib
import sys

# name -> ("module:function", help). Each function takes the remaining argv and returns an exit code.
COMMANDS: dict[str, tuple[str, str]] = {
    "run": ("pillagerbench.cli:run_main", "play a match between two teams and record it"),
    "setup": ("pillagerbench.node:setup_main", "install the pinned Node packages into the cache"),
    "server": ("pillagerbench.arena.serve:main", "start an arena server to watch with a 1.16.5 client"),
    "try": ("pillagerbench.players.try_code:main", "run a JavaScript file as one player and print its events"),
    "llm-ping": ("pillagerbench.llm.ping:main", "send one short request to an LLM provider"),
    "report": ("pillagerbench.report.build:main", "tables, figures and an HTML page from run directories"),
    "calibrate": ("pillagerbench.metrics.calibration:main", "σ_blue for the sabotage metric (runs or plays do_nothing vs every opponent)"),
}


def run_main(argv: list[str]) -> int:
    """`pillagerbench run`: one match (run.py), or many series with experiment=/resume= (experiments/)."""
    from pillagerbench.config import load_config

    cfg = load_config(argv)
    if cfg.get("experiment") is not None or cfg.get("resume"):  # many series, parallel, resumable
        from pillagerbench.experiments.runner import main_experiment

        return main_experiment(cfg, argv)
    from pillagerbench.run import run_match

    return run_match(cfg)


def usage() -> str:
    lines = ["usage: pillagerbench <command> [key=value ...]", "", "commands:"]
    lines += [f"  {name:<10} {help_}" for name, (_, help_) in COMMANDS.items()]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0] in ("-h", "--help", "help"):
        print(usage())
        return 0
    name, rest = argv[0], argv[1:]
    if name not in COMMANDS:
        print(f"pillagerbench: unknown command {name!r}; valid commands: {', '.join(COMMANDS)}",
              file=sys.stderr)
        return 2
    module_name, func_name = COMMANDS[name][0].split(":")
    func = getattr(importlib.import_module(module_name), func_name)
    from pillagerbench.config import ConfigError

    try:
        return int(func(rest) or 0)
    except ConfigError as exc:
        print(f"pillagerbench {name}: bad configuration: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":
    sys.exit(main())
