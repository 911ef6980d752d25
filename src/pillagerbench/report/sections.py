"""The report's parts (report/build.py lists them in page order): a table, a figure or markup."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd

from pillagerbench.report import tables


@dataclass
class Section:
    """One part of the report, in page order: a table (written as NAME.csv and NAME.md), a figure
    (content: (png path, caption)) or markup; on the page and in its contents unless empty."""

    title: str
    kind: str  # "table" | "image" | "html"
    content: Any
    name: str | None = None
    empty: bool = False

    def files(self, out: Path) -> list[Path]:
        if self.kind == "table":
            return tables.write(self.content, out, str(self.name), self.title)
        return [self.content[0]] if self.kind == "image" else []


def table(name: str, title: str, frame: pd.DataFrame) -> Section:
    return Section(title, "table", frame, name, empty=not len(frame))


def figure(title: str, path: Path, caption: str, episodes: int) -> Section:
    return Section(title, "image", (path, caption), empty=not episodes)
