"""Agent code from LLM answers: pull out the JavaScript blocks, parse them with a real JavaScript
parser (acorn, pinned in js/package.json) and turn each into a program a player can run.

    blocks = extract_code_blocks(answer.text)             # fenced ```javascript / ```js blocks
    program = check_program(blocks[0], allowed=scenario.primitives)   # raises CodeError(reason)
    events = await player.run(program.exec_code)

A program keeps the block's top-level function declarations (anything else at the top level is
dropped, as upstream did); its entry point is the last top-level `async function` whose first
parameter is `bot`, and `exec_code` is the functions followed by `await <entry>(bot);` (player code
runs as the body of an async function). A program is rejected when it does not parse, has no entry
point, or calls a primitive the scenario does not allow (or, by default, a function defined nowhere).

Parsing goes through one long-lived Node process per Python process (`JSParser.shared()`), a
few milliseconds per check after a ~50 ms start.
"""

from __future__ import annotations

import atexit
import json
import subprocess
import threading
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

from pillagerbench.host.node import JS_DIR
from pillagerbench.players import primitives as prim

# What agent code may reference without defining it: the sandbox's names, declared once in
# js/bot/sandbox_globals.json (js/bot/sandbox.js gives agent code exactly these)
SANDBOX_NAMES = frozenset(json.loads((JS_DIR / "bot" / "sandbox_globals.json").read_text(encoding="utf-8")))
# ... and the ECMAScript built-ins every vm context has
JS_BUILTINS = frozenset(
    {
        "Array",
        "ArrayBuffer",
        "BigInt",
        "Boolean",
        "DataView",
        "Date",
        "Error",
        "EvalError",
        "Float32Array",
        "Float64Array",
        "Int8Array",
        "Int16Array",
        "Int32Array",
        "Intl",
        "JSON",
        "Map",
        "Math",
        "Number",
        "Object",
        "Promise",
        "Proxy",
        "RangeError",
        "ReferenceError",
        "Reflect",
        "RegExp",
        "Set",
        "String",
        "Symbol",
        "SyntaxError",
        "TypeError",
        "URIError",
        "Uint8Array",
        "Uint8ClampedArray",
        "Uint16Array",
        "Uint32Array",
        "WeakMap",
        "WeakSet",
        "AggregateError",
        "decodeURI",
        "decodeURIComponent",
        "encodeURI",
        "encodeURIComponent",
        "isFinite",
        "isNaN",
        "parseFloat",
        "parseInt",
        "structuredClone",
        "queueMicrotask",
        "globalThis",
    }
)

_PARSER_JS = r"""
const acorn = require('acorn')
const readline = require('readline')
const OPTIONS = { ecmaVersion: 'latest', sourceType: 'script', allowAwaitOutsideFunction: true,
  allowReturnOutsideFunction: true, locations: true }

function patternNames (p, out) {
  if (!p) return
  switch (p.type) {
    case 'Identifier': out.add(p.name); break
    case 'ObjectPattern': for (const prop of p.properties) patternNames(prop.type === 'RestElement' ? prop.argument : prop.value, out); break
    case 'ArrayPattern': for (const e of p.elements) patternNames(e, out); break
    case 'RestElement': patternNames(p.argument, out); break
    case 'AssignmentPattern': patternNames(p.left, out); break
  }
}

function dotted (node) {
  if (node.type === 'Identifier') return node.name
  if (node.type === 'ThisExpression') return 'this'
  if (node.type === 'MemberExpression' && !node.computed) {
    const obj = dotted(node.object)
    return obj === null ? null : `${obj}.${node.property.name}`
  }
  if (node.type === 'MemberExpression') {
    const obj = dotted(node.object)
    return obj === null ? null : `${obj}[]`
  }
  return null
}

function analyse (code) {
  const ast = acorn.parse(code, OPTIONS)
  const functions = []
  const others = []
  for (const node of ast.body) {
    if (node.type === 'FunctionDeclaration') {
      functions.push({ name: node.id.name, async: node.async, generator: node.generator,
        params: node.params.map(p => p.type === 'Identifier' ? p.name : (p.type === 'AssignmentPattern' && p.left.type === 'Identifier' ? p.left.name : null)),
        start: node.start, end: node.end, line: node.loc.start.line })
    } else if (node.type !== 'EmptyStatement') {
      others.push({ type: node.type, line: node.loc.start.line, text: code.slice(node.start, Math.min(node.end, node.start + 80)) })
    }
  }
  const calls = new Set(); const members = new Set(); const declared = new Set()
  const stack = [ast]
  while (stack.length) {
    const node = stack.pop()
    if (!node || typeof node.type !== 'string') continue
    switch (node.type) {
      case 'CallExpression': case 'NewExpression': {
        const name = dotted(node.callee)
        if (name !== null) (node.callee.type === 'Identifier' ? calls : members).add(name)
        break
      }
      case 'FunctionDeclaration': case 'FunctionExpression': case 'ArrowFunctionExpression':
        if (node.id) declared.add(node.id.name)
        for (const p of node.params) patternNames(p, declared)
        break
      case 'ClassDeclaration': case 'ClassExpression': if (node.id) declared.add(node.id.name); break
      case 'VariableDeclarator': patternNames(node.id, declared); break
      case 'CatchClause': patternNames(node.param, declared); break
    }
    for (const key of Object.keys(node)) {
      if (key === 'loc') continue
      const v = node[key]
      if (Array.isArray(v)) { for (const c of v) if (c && typeof c.type === 'string') stack.push(c) }
      else if (v && typeof v.type === 'string') stack.push(v)
    }
  }
  return { ok: true, functions, others, calls: [...calls].sort(), members: [...members].sort(), declared: [...declared].sort() }
}

const rl = readline.createInterface({ input: process.stdin, crlfDelay: Infinity })
rl.on('line', line => {
  let req
  try { req = JSON.parse(line) } catch (e) { return }
  let out
  try { out = analyse(req.code) } catch (e) {
    out = { ok: false, error: `${e.name}: ${e.message}`, line: e.loc ? e.loc.line : null, column: e.loc ? e.loc.column : null }
  }
  process.stdout.write(JSON.stringify({ id: req.id, ...out }) + '\n')
})
"""


class CodeError(ValueError):
    """Code that cannot be used; the message is the reason (recorded in the episode's artefacts)."""


@dataclass(frozen=True)
class JSFunction:
    name: str
    is_async: bool
    params: tuple[str | None, ...]
    start: int
    end: int
    line: int


@dataclass(frozen=True)
class ParsedJS:
    """What the parser found in one piece of code (`ok=False`: a syntax error, see `error`)."""

    ok: bool
    error: str | None = None
    line: int | None = None
    column: int | None = None
    functions: tuple[JSFunction, ...] = ()
    others: tuple[dict, ...] = ()  # top-level statements that are not function declarations
    calls: tuple[str, ...] = ()  # plain identifiers called anywhere: foo(...), new Foo(...)
    members: tuple[str, ...] = ()  # member calls: "bot.chat", "bot.pathfinder.goto", "x[]"
    declared: tuple[str, ...] = ()  # every name bound anywhere (functions, variables, params)


class JSParser:
    """A long-lived Node process parsing JavaScript with acorn. Thread-safe; restarts if it dies."""

    _shared: JSParser | None = None
    _shared_lock = threading.Lock()

    def __init__(self) -> None:
        self._proc: subprocess.Popen | None = None
        self._lock = threading.Lock()
        self._next_id = 0

    @classmethod
    def shared(cls) -> JSParser:
        with cls._shared_lock:
            if cls._shared is None:
                cls._shared = JSParser()
                atexit.register(cls._shared.close)
            return cls._shared

    def _start(self) -> subprocess.Popen:
        from pillagerbench.host.node import node_binary, node_env

        return subprocess.Popen(
            [str(node_binary()), "-e", _PARSER_JS],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            env=node_env(),
            text=True,
            encoding="utf-8",
            bufsize=1,
        )

    def parse(self, code: str) -> ParsedJS:
        with self._lock:
            for _attempt in range(2):
                if self._proc is None or self._proc.poll() is not None:
                    self._proc = self._start()
                self._next_id += 1
                stdin, stdout = self._proc.stdin, self._proc.stdout
                assert stdin is not None and stdout is not None  # _start opens both as pipes
                try:
                    stdin.write(json.dumps({"id": self._next_id, "code": code}) + "\n")
                    stdin.flush()
                    line = stdout.readline()
                except (BrokenPipeError, OSError):
                    line = ""
                if line:
                    break
                self.close_locked()
            else:
                raise RuntimeError("the JavaScript parser process (node + acorn) did not answer")
        data = json.loads(line)
        if not data.get("ok"):
            return ParsedJS(False, data.get("error"), data.get("line"), data.get("column"))
        return ParsedJS(
            True,
            functions=tuple(
                JSFunction(f["name"], f["async"], tuple(f["params"]), f["start"], f["end"], f["line"])
                for f in data["functions"]
            ),
            others=tuple(data["others"]),
            calls=tuple(data["calls"]),
            members=tuple(data["members"]),
            declared=tuple(data["declared"]),
        )

    def close_locked(self) -> None:
        proc, self._proc = self._proc, None
        if proc is not None:
            try:
                if proc.stdin is not None:
                    proc.stdin.close()
            except OSError:
                pass
            try:
                proc.kill()
                proc.wait(timeout=5)
            except (OSError, subprocess.TimeoutExpired):
                pass
            for stream in (proc.stdout,):
                try:
                    if stream is not None:
                        stream.close()
                except OSError:
                    pass

    def close(self) -> None:
        with self._lock:
            self.close_locked()


def parse_js(code: str) -> ParsedJS:
    """Parse with the shared parser process."""
    return JSParser.shared().parse(code)


def extract_code_blocks(text: str, languages: Iterable[str] = ("javascript", "js")) -> list[str]:
    """The contents of the fenced code blocks tagged with one of `languages` (case-insensitive), in order.
    An untagged block counts too when the answer has no tagged block. A block left open at the end
    of the answer (a truncated answer) is ignored."""
    langs = {lang.lower() for lang in languages}
    tagged: list[str] = []
    untagged: list[str] = []
    lines = text.replace("\r\n", "\n").split("\n")
    i = 0
    while i < len(lines):
        stripped = lines[i].strip()
        if stripped.startswith("```"):
            fence = stripped[: len(stripped) - len(stripped.lstrip("`"))]
            tag = stripped[len(fence) :].strip().split(" ")[0].lower()
            body: list[str] = []
            j = i + 1
            while j < len(lines) and not (lines[j].strip().startswith(fence) and lines[j].strip().strip("`") == ""):
                body.append(lines[j])
                j += 1
            if j >= len(lines):
                break  # never closed
            code = "\n".join(body).strip("\n")
            if tag in langs:
                tagged.append(code)
            elif tag == "":
                untagged.append(code)
            i = j + 1
            continue
        i += 1
    return tagged or untagged


@dataclass(frozen=True)
class Program:
    """One player's checked code."""

    source: str  # the block as the LLM wrote it
    code: str  # its top-level function declarations
    entry: str  # the entry point's name
    functions: tuple[str, ...]
    primitives: tuple[str, ...]  # primitive functions it calls
    dropped: tuple[str, ...] = ()  # top-level statements that were left out
    warnings: tuple[str, ...] = field(default_factory=tuple)

    @property
    def exec_code(self) -> str:
        """What `player.run` executes."""
        return f"{self.code}\n\nawait {self.entry}(bot);\n"

    def to_dict(self) -> dict:
        return {
            "entry": self.entry,
            "functions": list(self.functions),
            "primitives": list(self.primitives),
            "dropped": list(self.dropped),
            "warnings": list(self.warnings),
            "code": self.code,
            "exec_code": self.exec_code,
        }


def allowed_functions(allowed: Sequence[str] | None) -> set[str]:
    """Primitive function names available for the given modules / function names (None: all)."""
    return set(prim.functions(list(allowed) if allowed is not None else None))


def check_program(
    source: str, allowed: Sequence[str] | None = None, *, parser: JSParser | None = None, reject_undefined: bool = True
) -> Program:
    """Check one code block and make it a Program, or raise CodeError with the reason.

    `allowed`: the scenario's primitive modules (or function names); None allows every primitive."""
    if not source.strip():
        raise CodeError("the code block is empty")
    parsed = (parser or JSParser.shared()).parse(source)
    if not parsed.ok:
        where = f" (line {parsed.line}, column {parsed.column})" if parsed.line else ""
        raise CodeError(f"the code does not parse: {parsed.error}{where}")
    entries = [f for f in parsed.functions if f.is_async and f.params and f.params[0] == "bot"]
    if not entries:
        raise CodeError(
            "no entry point: the code needs a top-level `async function` taking `bot` (the last one is run)"
        )
    entry = entries[-1]
    every_primitive = allowed_functions(None)
    usable = allowed_functions(allowed)
    defined = set(parsed.declared)
    top = {f.name for f in parsed.functions}
    forbidden = sorted(c for c in parsed.calls if c in every_primitive and c not in usable and c not in top)
    if forbidden:
        raise CodeError(
            f"calls primitive(s) not available in this scenario: {', '.join(forbidden)} "
            f"(available: {', '.join(sorted(usable))})"
        )
    unknown = sorted(
        c
        for c in parsed.calls
        if c not in every_primitive and c not in defined and c not in SANDBOX_NAMES and c not in JS_BUILTINS
    )
    warnings: list[str] = []
    if unknown:
        msg = f"calls function(s) defined nowhere: {', '.join(unknown)}"
        if reject_undefined:
            raise CodeError(msg)
        warnings.append(msg)
    code = "\n\n".join(source[f.start : f.end] for f in parsed.functions)
    dropped = tuple(f"line {o['line']}: {o['text']}" for o in parsed.others)
    if dropped:
        warnings.append(f"{len(dropped)} top-level statement(s) outside functions were left out")
    used = tuple(sorted(c for c in parsed.calls if c in usable and c not in top))
    return Program(
        source=source,
        code=code,
        entry=entry.name,
        functions=tuple(f.name for f in parsed.functions),
        primitives=used,
        dropped=dropped,
        warnings=tuple(warnings),
    )


@dataclass
class ProgramsResult:
    """Per player: a Program or None, and why not."""

    programs: list[Program | None]
    problems: list[str]  # one line per problem, naming the player
    blocks: list[str]

    @property
    def complete(self) -> bool:
        return all(p is not None for p in self.programs)

    @property
    def usable(self) -> int:
        return sum(p is not None for p in self.programs)


def idle_problem(program: Program) -> str | None:
    """Why a program does nothing (e.g. the answer format's empty `main` copied as it is), or None."""
    parsed = parse_js(program.code)
    if not parsed.calls and not parsed.members:
        return f"the code does nothing: `{program.entry}` calls no function at all"
    return None


def programs_from_answer(
    text: str,
    players: Sequence[str],
    allowed: Sequence[str] | None = None,
    *,
    parser: JSParser | None = None,
    reject_undefined: bool = True,
    reject_idle: bool = False,
) -> ProgramsResult:
    """Code block k is player k's program. Missing or bad blocks leave that player with None, and with
    `reject_idle` a program that does nothing too."""
    blocks = extract_code_blocks(text)
    programs: list[Program | None] = []
    problems: list[str] = []
    if not blocks:
        problems.append("the answer has no ```javascript code block")
    elif len(blocks) < len(players):
        problems.append(f"the answer has {len(blocks)} code block(s) for {len(players)} players")
    elif len(blocks) > len(players):
        problems.append(
            f"the answer has {len(blocks)} code blocks for {len(players)} players; the extra ones were ignored"
        )
    for k, name in enumerate(players):
        if k >= len(blocks):
            programs.append(None)
            if blocks:
                problems.append(f"{name}: no code block")
            continue
        try:
            program = check_program(blocks[k], allowed, parser=parser, reject_undefined=reject_undefined)
            idle = idle_problem(program) if reject_idle else None
            if idle is not None:
                raise CodeError(idle)
            programs.append(program)
        except CodeError as exc:
            programs.append(None)
            problems.append(f"{name}: {exc}")
    return ProgramsResult(programs, problems, blocks)
