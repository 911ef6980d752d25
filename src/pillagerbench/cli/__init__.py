"""The command line: `pillagerbench COMMAND` (commands.py), each command's help (help.py), `layout show`."""

from pillagerbench.cli.commands import main

__all__ = ["main"]
