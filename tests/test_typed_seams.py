"""No `Any` at a seam (issue 40, item 5): the public signatures of the modules of the packages the
layers meet through (match, agents, teams, scenarios, players) name real types, so mypy checks what
crosses between them.

Read with `ast` from the source (annotations are strings under `from __future__ import annotations`):
every public function and method (and `__init__`), and every public class attribute (dataclass
fields, Protocol members). An annotation carries `Any` when it is `Any` itself or a union or Optional
with `Any` in it (`Any | None`), a `**kwargs: Any` or `*args: Any` included. `Any` as the value type
of a JSON object (`dict[str, Any]`, `list[Any]`) is data read from a file or the wire, not a seam,
and is allowed.

`teams/registry.py` is left out: its functions take the configuration node, which item 1 of the issue
types (the typed configuration model); the registry type (item 3) rewrites the module.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "pillagerbench"
SEAMS = ("match", "agents", "teams", "scenarios", "players")
CONFIG_EDGE = ("teams/registry.py",)


def _names_any(node: ast.expr | None) -> bool:
    """True when the annotation is Any, or a union / Optional one of whose members is."""
    if node is None:
        return False
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return _names_any(ast.parse(node.value, mode="eval").body)
    if isinstance(node, ast.Name):
        return node.id == "Any"
    if isinstance(node, ast.Attribute):
        return node.attr == "Any"
    if isinstance(node, ast.BinOp):  # X | Y
        return _names_any(node.left) or _names_any(node.right)
    if isinstance(node, ast.Subscript) and ast.unparse(node.value).split(".")[-1] in ("Optional", "Union"):
        members = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
        return any(_names_any(m) for m in members)
    return False


def _public(name: str) -> bool:
    return not name.startswith("_") or name == "__init__"


def any_in_signatures(source: str) -> list[str]:
    """`name(param: annotation)`, `name -> annotation` and `Class.attribute: annotation` of every
    public signature in `source` that carries Any."""
    found: list[str] = []

    def visit(body: list[ast.stmt], prefix: str, in_class: bool) -> None:
        for node in body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and _public(node.name):
                a = node.args
                params = [*a.posonlyargs, *a.args, *a.kwonlyargs, *(p for p in (a.vararg, a.kwarg) if p)]
                found.extend(
                    f"{prefix}{node.name}({p.arg}: {ast.unparse(p.annotation)})"
                    for p in params
                    if p.annotation is not None and _names_any(p.annotation)
                )
                if _names_any(node.returns):
                    found.append(f"{prefix}{node.name} -> {ast.unparse(node.returns)}")  # type: ignore[arg-type]
            elif isinstance(node, ast.ClassDef) and not node.name.startswith("_"):
                visit(node.body, f"{prefix}{node.name}.", True)
            elif (
                in_class
                and isinstance(node, ast.AnnAssign)
                and isinstance(node.target, ast.Name)
                and not node.target.id.startswith("_")
                and _names_any(node.annotation)
            ):
                found.append(f"{prefix}{node.target.id}: {ast.unparse(node.annotation)}")

    visit(ast.parse(source).body, "", False)
    return found


def test_no_any_in_the_public_signatures_of_the_seams():
    found = [
        f"{path.relative_to(PACKAGE).as_posix()}: {where}"
        for package in SEAMS
        for path in sorted((PACKAGE / package).rglob("*.py"))
        if path.relative_to(PACKAGE).as_posix() not in CONFIG_EDGE
        for where in any_in_signatures(path.read_text(encoding="utf-8"))
    ]
    assert not found, "Any in a public signature (give it a real type: a Protocol, a dataclass, a TypedDict):\n" + (
        "\n".join(found)
    )


def test_the_check_finds_any_at_a_seam():
    source = """
from typing import Any, Optional

def fine(data: dict[str, Any], n: int) -> list[Any]: ...
def _private(x: Any) -> Any: ...
def param(llm: Any) -> None: ...
def maybe(llm: "Any | None" = None) -> None: ...
def old(llm: Optional[Any]) -> None: ...
async def answer(**kw: Any) -> Any: ...

class Scenario:
    layout: Any = None
    _cache: Any = None
    rules: dict[str, Any]

    def __init__(self, client: Any): ...
    def _helper(self, x: Any) -> Any: ...
"""
    assert any_in_signatures(source) == [
        "param(llm: Any)",
        "maybe(llm: 'Any | None')",
        "old(llm: Optional[Any])",
        "answer(kw: Any)",
        "answer -> Any",
        "Scenario.layout: Any",
        "Scenario.__init__(client: Any)",
    ]


# The configuration is typed to its leaves (issue 53, item 1): outside config/ no module turns the typed
# configuration back into a dict (`.stored()`, `plain(`) or composes one untyped (`to_dict(load_config`);
# config/validate.py gives the typed RunConfig, its groups and the server's keys. The one exception is
# rundir/manifest.py, the writer of a run's stored configuration and the reader of old manifests' (a dict).
CONFIG_AS_DICT = re.compile(r"\.stored\(\)|\bplain\(|to_dict\(load_config")
STORED_CONFIG = "rundir/manifest.py"
# left to do (issue 53, item 1): none. This list may only shrink: an entry without a hit fails too.
CONFIG_AS_DICT_LEFT: set[str] = set()


def _config_as_dict() -> dict[str, list[str]]:
    found: dict[str, list[str]] = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE).as_posix()
        if rel.startswith("config/"):
            continue
        for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            code = line.split("#", 1)[0]
            if CONFIG_AS_DICT.search(code):
                found.setdefault(rel, []).append(f"{rel}:{i}: {line.strip()}")
    return found


def test_no_configuration_dict_outside_config():
    found = _config_as_dict()
    new = [
        hit for rel, hits in found.items() if rel != STORED_CONFIG and rel not in CONFIG_AS_DICT_LEFT for hit in hits
    ]
    assert not new, "take the typed RunConfig (config/validate.py, config/schema.py), not a dict of it:\n" + "\n".join(
        new
    )
    done = sorted(CONFIG_AS_DICT_LEFT - set(found))
    assert not done, f"no configuration dict left in {done}: take it off CONFIG_AS_DICT_LEFT"
