"""No function longer than 80 lines and no class longer than 300 lines, in src/ or tests/ (issue 30,
item 6; issue 40, item 7). There is no list of exemptions: CONTRIBUTING.md says why.

A function's or class's length is `end_lineno - lineno + 1` of its `def` or `class` (decorators not
counted, docstring and nested definitions counted). A longer one wants splitting along its own steps
(a function) or its own concerns (a class: its parts become collaborators in files of their own).
"""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CHECKED = (ROOT / "src", ROOT / "tests")
MAX_LINES = 80
MAX_CLASS_LINES = 300


def long_definitions(
    root: Path, max_lines: int = MAX_LINES, max_class_lines: int = MAX_CLASS_LINES
) -> list[tuple[str, str, int]]:
    """(file relative to root, qualified name, lines) of every function longer than max_lines and
    every class longer than max_class_lines."""
    found: list[tuple[str, str, int]] = []
    for path in sorted(root.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for name, is_class, lines in _definitions(tree, ""):
            if lines > (max_class_lines if is_class else max_lines):
                found.append((path.relative_to(root).as_posix(), name, lines))
    return found


def _definitions(node: ast.AST, prefix: str) -> list[tuple[str, bool, int]]:
    """(qualified name, is a class, lines) of the functions and classes under node, nested ones included."""
    out: list[tuple[str, bool, int]] = []
    for child in ast.iter_child_nodes(node):
        if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            name = f"{prefix}{child.name}"
            out.append((name, isinstance(child, ast.ClassDef), (child.end_lineno or child.lineno) - child.lineno + 1))
            out += _definitions(child, f"{name}.")
        else:
            out += _definitions(child, prefix)
    return out


def test_no_function_over_80_lines_and_no_class_over_300():
    too_long = [f"{root.name}/{rel}: {name} ({n} lines)" for root in CHECKED for rel, name, n in long_definitions(root)]
    assert not too_long, (
        f"functions over {MAX_LINES} lines or classes over {MAX_CLASS_LINES} (split them along their steps or "
        "concerns; there are no exemptions):\n" + "\n".join(too_long)
    )


def _body(n: int, indent: str) -> str:
    return "\n".join(f"{indent}x{i} = {i}" for i in range(n))


def test_the_checker_finds_a_long_function(tmp_path):
    (tmp_path / "m.py").write_text(
        f"def fits():\n{_body(MAX_LINES - 1, '    ')}\n\n\n"  # 80 lines with its def
        f"class C:\n    async def long(self):\n{_body(MAX_LINES, '        ')}\n",  # 81 lines
        encoding="utf-8",
    )
    assert long_definitions(tmp_path) == [("m.py", "C.long", MAX_LINES + 1)]


def test_the_checker_finds_a_long_class(tmp_path):
    """A class of short methods is still caught when the class itself is too long; one of 300 lines is not."""
    methods = MAX_CLASS_LINES // 10  # each method 10 lines: def + 9 body lines
    fits = "".join(f"    def m{k}(self):\n{_body(9, '        ')}\n" for k in range(methods - 1))
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "m.py").write_text(
        f"class Fits:\n{fits}{_body(9, '    ')}\n\n\n"  # 1 + 290 + 9 = 300 lines
        f"class Long:\n{fits}{_body(10, '    ')}\n",  # 301 lines
        encoding="utf-8",
    )
    assert long_definitions(tmp_path) == [("sub/m.py", "Long", MAX_CLASS_LINES + 1)]
