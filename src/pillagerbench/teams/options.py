"""A team's options, declared once: a pydantic model per team (`Team.Options`), one field per option
with its type, its range, its default and a one-line description (`Field(..., description=...)`).

The team's constructor reads its options through the model; `match/validate.py` (registered into config/validate.py) checks `red.KEY=VALUE`,
`experiment.team_options.KEY=VALUE` and a league entrant's options against it; `pillagerbench teams`
and `run --help` list its defaults. A built-in team's `conf/team/<name>.yaml` (Hydra needs one file
per team to select `red=NAME`) repeats the fields as `key: default  # description`, and
tests/teams/test_options.py fails when the two differ (`yaml_lines` is the text the file should have).

An outside team may instead set `options_declared = {"key": default}`; its types are then the types
of the defaults (`null`: any value).
"""

from __future__ import annotations

import json
from typing import Any

from pydantic import BaseModel, ConfigDict, create_model


class TeamOptions(BaseModel):
    """No options. A team's own model subclasses this and adds one field per option."""

    model_config = ConfigDict(extra="forbid", protected_namespaces=())


def _option_type(default: Any) -> Any:
    if default is None:
        return Any
    if isinstance(default, bool):
        return bool
    if isinstance(default, float):
        return float
    return type(default)


def options_model(cls: type) -> type[TeamOptions]:
    """The options model of a team class: its `Options`, or one built from `options_declared`."""
    declared = getattr(cls, "options_declared", None) or {}
    model: type[TeamOptions] = getattr(cls, "Options", TeamOptions)
    if declared and model is TeamOptions:
        fields: dict[str, Any] = {k: (_option_type(v), v) for k, v in declared.items()}
        return create_model(f"{getattr(cls, 'name', 'team')}_options", __base__=TeamOptions, **fields)
    return model


def defaults(model: type[BaseModel]) -> dict[str, Any]:
    """The options with their defaults, in declaration order."""
    return {k: f.get_default(call_default_factory=True) for k, f in model.model_fields.items()}


def yaml_lines(model: type[BaseModel]) -> list[str]:
    """The options as lines of a conf/team YAML file: `key: default  # description`."""
    width = max((len(k) + len(json.dumps(v)) for k, v in defaults(model).items()), default=0) + 4
    out = []
    for key, value in defaults(model).items():
        line = f"{key}: {json.dumps(value)}"
        description = model.model_fields[key].description
        out.append(f"{line.ljust(width)}# {description}" if description else line)
    return out
