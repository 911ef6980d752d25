"""The argument parser of the commands that take switches (report, fidelity, export, ...): argparse
whose mistakes (an unknown switch, a missing argument) are a `UsageError`, which `pillagerbench`
prints as one line with exit 2, never argparse's usage block and a bare exit."""

from __future__ import annotations

import argparse
from typing import NoReturn


class UsageError(ValueError):
    """A command line its parser cannot read; the message says what and how to get help."""


class Parser(argparse.ArgumentParser):
    def __init__(self, prog: str, description: str | None = None) -> None:
        super().__init__(prog=prog, description=description, allow_abbrev=False)  # `--mix` is not `--mix-suites`

    def error(self, message: str) -> NoReturn:
        raise UsageError(f"{message} (see {self.prog} --help)")
