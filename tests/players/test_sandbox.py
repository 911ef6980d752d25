"""Bad agent code: each case gives a clear onError (or a refusal from the server), never a crash of
the benchmark, a lost event, or an effect on another player."""

from __future__ import annotations

import asyncio
import json
import os
import signal
import time

import pytest
import pytest_asyncio

from pillagerbench.agents.code import SANDBOX_NAMES
from pillagerbench.players import primitives as prim
from pillagerbench.players.events import chat_log, chats_by, errors, last_observation
from tests.players.conftest import Area, close_players, count, start_player
from tests.support.node_script import run_node_script


@pytest.fixture
async def pair(server, area, make_player):
    """A player for the bad code and a bystander running ordinary code at the same time: fresh ones, for
    the tests that restart or kill the bot, or fill its chat limit."""
    bad = await make_player(area, 0, 0, {"bread": 1})
    other = await make_player(area, 6, 0, {"bread": 5})
    return bad, other


@pytest_asyncio.fixture(scope="module", loop_scope="session")
async def calm_pair(server, tmp_path_factory):
    """As `pair`, one for the whole module: the tests whose bad code gets an error, not a restart, share
    it (every run has a fresh sandbox context; starting two bots per test cost 3-4 s). Each such test
    checks that its own code restarted nothing."""
    area, made = Area(server), []
    log_dir = tmp_path_factory.mktemp("calm_pair")
    bad = await start_player(server, area, log_dir, made, 0, 0, {"bread": 1})
    other = await start_player(server, area, log_dir, made, 6, 0, {"bread": 5})
    yield bad, other
    await close_players(server, made)


@pytest.fixture
def shared(calm_pair):
    """The module's pair; fails the test if its code restarted either bot."""
    restarts = [p.bot.restarts for p in calm_pair]
    yield calm_pair
    assert [p.bot.restarts for p in calm_pair] == restarts and all(p.bot.alive for p in calm_pair)


async def _bystander_ok(other):
    events = await other.run("bot.chat('still here'); return 1")
    assert errors(events) == []
    assert "still here" in chats_by(events, other.name)


async def test_syntax_error_points_at_line(shared):
    bad, other = shared
    events = await bad.run("const a = 1\nconst b = ;\n")
    assert events[-1][0] == "observe"
    (err,) = errors(events)
    assert err.startswith("SyntaxError") and "at line 2: const b = ;" in err
    await _bystander_ok(other)


async def test_thrown_exception_points_at_line(shared):
    bad, _ = shared
    events = await bad.run("async function f() {\n  throw new Error('boom')\n}\nawait f()")
    (err,) = errors(events)
    assert err == "Error: boom\nat line 2: throw new Error('boom')"
    events = await bad.run("throw 'a string'")
    assert errors(events) == ['Error: "a string"']


async def test_sync_endless_loop_is_stopped_without_restart(pair):
    bad, other = pair
    t0 = time.perf_counter()
    events = await bad.run("let i = 0\nwhile (true) { i++ }")
    assert time.perf_counter() - t0 < 3
    assert "endless loop" in errors(events)[0]
    assert bad.bot.restarts == 0
    await _bystander_ok(other)


async def test_async_endless_loop_restarts_the_bot(server, pair):
    bad, other = pair
    before = await count(server, bad.name, "bread")
    other_run = asyncio.create_task(other.run("await bot.waitForTicks(40); bot.chat('done waiting')"))
    t0 = time.perf_counter()
    events = await bad.run("await bot.waitForTicks(1)\nwhile (true) {}")
    took = time.perf_counter() - t0
    assert took < 6, took
    assert bad.bot.restarts == 1 and bad.bot.alive
    assert "blocked the bot" in errors(events)[0]
    assert events[-1][0] == "observe"
    assert await count(server, bad.name, "bread") == before  # state restored after the restart
    other_events = await other_run
    assert errors(other_events) == [] and "done waiting" in chats_by(other_events, other.name)
    events = await bad.run("bot.chat('back again')")  # the player works after the restart
    assert "back again" in chats_by(events, bad.name)
    events = await bad.run("while (true) { await Promise.resolve() }")  # microtask loop
    assert "blocked the bot" in errors(events)[0] and bad.bot.restarts == 2


async def test_unhandled_rejection(shared):
    bad, _ = shared
    events = await bad.run("Promise.reject(new Error('lost promise'))\nawait bot.waitForTicks(5)")
    assert any("lost promise" in e for e in errors(events))
    events = await bad.run("setTimeout(() => { throw new Error('in a timer') }, 10)\nawait bot.waitForTicks(10)")
    assert any("in a timer" in e for e in errors(events))


@pytest.mark.parametrize(
    "code, expected",
    [
        ("require('fs')", "ReferenceError: require is not defined"),
        ("process.exit(1)", "ReferenceError: process is not defined"),
        ("bot.constructor.constructor('return process')().exit(1)", "EvalError"),
        ("bot.chat.constructor('return process')().exit(1)", "EvalError"),
        ("this.constructor.constructor('return process')()", "EvalError"),
        ("mineBlock.constructor('return process')()", "EvalError"),
        ("(async () => {}).constructor('return 1')()", "EvalError"),
        ("eval('1 + 1')", "EvalError"),
        ("bot.entity.position.constructor.constructor('return process')()", "EvalError"),
        (
            "const e = await mineBlock(bot, 'x').catch(e => e)\ne.constructor.constructor('return process')()",
            "EvalError",
        ),
        ("bot._client.write('chat', {message: 'raw'})", "TypeError"),
        ("await import('fs')", "TypeError"),
    ],
)
async def test_escape_attempts(shared, code, expected):
    bad, other = shared
    restarts = bad.bot.restarts
    events = await bad.run(code)
    errs = errors(events)
    assert errs and errs[0].startswith(expected), errs
    assert bad.bot.restarts == restarts and bad.bot.alive


async def test_a_bot_process_that_exits_mid_run_is_reported_and_restarted(pair):
    """Even if something reached the host realm and ended the bot process (here: a signal from
    outside, as agent code cannot), the run reports it, the player comes back with its inventory, and
    the bystander plays on."""
    bad, other = pair
    running = asyncio.Event()
    run = asyncio.create_task(
        bad.run("bot.chat('started')\nawait bot.waitForTicks(400)", on_event=lambda e: running.set())
    )
    await asyncio.wait_for(running.wait(), 10)  # the code is running
    assert bad.bot.proc is not None
    os.kill(bad.bot.proc.pid, signal.SIGTERM)
    events = await asyncio.wait_for(run, 30)
    assert "the bot process ended" in errors(events)[0] and "restarted" in errors(events)[0], errors(events)
    assert last_observation(events)["inventory"] == {"bread": 1}
    assert bad.bot.alive and bad.bot.restarts == 1
    assert "back again" in chats_by(await bad.run("bot.chat('back again')"), bad.name)
    await _bystander_ok(other)


async def test_memory_bomb(pair):
    bad, other = pair
    events = await bad.run("const a = []\nwhile (true) a.push(new Array(1e6).fill(1.5))")
    errs = errors(events)
    assert errs, events
    assert "memory" in errs[0] or "endless loop" in errs[0] or "blocked the bot" in errs[0]
    assert bad.bot.alive
    # allocating between awaits: the heap limit ends the process; it is restarted with its inventory
    events = await bad.run(
        "await bot.waitForTicks(1)\nconst a = []\n"
        "for (let i = 0; ; i++) { a.push(new Array(1e5).fill(i)); if (i % 20 === 0) await bot.waitForTicks(1) }"
    )
    assert "ran out of memory" in errors(events)[0]
    assert last_observation(events)["inventory"] == {"bread": 1}
    assert bad.bot.alive and bad.bot.restarts >= 1
    events = await bad.run("'x'.repeat(2 ** 30)")
    assert "Invalid string length" in errors(events)[0]
    await _bystander_ok(other)


async def test_chat_commands_are_refused(server, pair):
    bad, other = pair
    events = await bad.run(
        f"bot.chat('/give {bad.name} diamond 64')\nbot.chat('/tp {other.name} 0 100 0')\nawait bot.waitForTicks(10)"
    )
    lines = chat_log(events)
    assert any("/give refused" in line for line in lines), lines
    assert any("/tp refused" in line for line in lines), lines
    assert await count(server, bad.name, "diamond") == 0
    pos = last_observation(await other.observe())["status"]["position"]
    assert pos["y"] < 10


async def test_chat_rate_limit(pair):
    bad, other = pair
    events = await bad.run("for (let i = 0; i < 30; i++) bot.chat('spam ' + i)")
    (err,) = errors(events)
    assert "Too many chats in short succession" in err and "at line 1" in err
    said = chats_by(events, bad.name)
    assert said == [f"spam {i}" for i in range(25)]  # every chat that went out comes back as an event
    await _bystander_ok(other)


async def test_timers_and_listeners_end_with_the_run(shared):
    bad, _ = shared
    events = await bad.run("setInterval(() => bot.chat('tick'), 100)\nbot.on('chat', () => bot.chat('echo'))\nreturn 1")
    assert errors(events) == []
    await asyncio.sleep(0.6)
    events = await bad.run("await bot.waitForTicks(4)")
    assert "tick" not in chats_by(events, bad.name) and "echo" not in chats_by(events, bad.name)


async def test_bot_process_runs_under_the_permission_model(shared):
    bad, _ = shared
    perms = await bad.channel.permissions()
    assert perms == {
        "enabled": True,
        "fsWrite": False,
        "fsReadRoot": False,
        "childProcess": False,
        "worker": False,
        "addons": False,
    }


# Routes to the host realm through the real host objects the facade hands out (issue 12). Each
# snippet returns what it reached; none may reach the bot (which holds `_client`, the raw protocol
# client and through its socket the network), `process`, its environment (`process.env`) or `require`.
STACK_FRAMES = """
const reached = []
const E = Error, R = RangeError
const grab = (e, frames) => { for (const f of frames) { try { const t = f.getThis(); if (t && t._client) reached.push('bot via ' + f.getFunctionName()) } catch (_) {} } return '' }
const probe = async (make) => {
  const point = { minus () { make().stack; return new Vec3(1, 0, 0) } }
  try { await bot.lookAt(point) } catch (_) {}
  try { bot.blockAt({ floored () { make().stack; return new Vec3(0, 3, 0) } }) } catch (_) {}
}
try { E.prepareStackTrace = grab } catch (_) {}
await probe(() => new E('probe'))
try { Object.defineProperty(E, 'prepareStackTrace', { value: grab }) } catch (_) {}
await probe(() => new R('probe'))
try { globalThis.Error = { prepareStackTrace: grab } } catch (_) {}
await probe(() => new R('probe'))
return reached
"""

PROTOTYPES = """
const refused = [], replaced = []
const protos = {
  EventEmitter: Object.getPrototypeOf(Object.getPrototypeOf(bot.inventory)),
  Entity: Object.getPrototypeOf(bot.entity),
  Vec3: Object.getPrototypeOf(bot.entity.position),
  Block: Object.getPrototypeOf(bot.blockAt(bot.entity.position.offset(0, -1, 0))),
  Object: Object.getPrototypeOf(Object.getPrototypeOf(Object.getPrototypeOf(bot.inventory))),
  Function: Object.getPrototypeOf(bot.chat),
  Array: Object.getPrototypeOf(bot.inventory.slots),
  Promise: Object.getPrototypeOf(bot.waitForTicks(1))
}
const spy = function () { if (this && this._client) replaced.push('bot'); return undefined }
for (const [name, proto] of Object.entries(protos)) {
  for (const key of ['emit', 'toString', 'apply', 'then', 'minus', 'push', 'newKey']) {
    try { proto[key] = spy; if (proto[key] === spy) replaced.push(name + '.' + key) } catch (_) { refused.push(name + '.' + key) }
    try { Object.defineProperty(proto, key, { value: spy }); replaced.push('define ' + name + '.' + key) } catch (_) {}
  }
}
bot.entity.position.minus = spy  // an instance's own property stays allowed (and harmless)
await bot.waitForTicks(5)
return { replaced, refused: refused.length }
"""

CALLER_CHAINS = """
const found = []
const climb = (fn) => { let f = fn; for (let i = 0; i < 12 && f; i++) { try { f = f.caller } catch (_) { return } if (f) { let args = []; try { args = Array.from(f.arguments || []) } catch (_) {} for (const a of args) if (a && (a._client || a.pid)) found.push(f.name) } } }
const point = { minus: function () { climb(point.minus); return new Vec3(1, 0, 0) } }
try { await bot.lookAt(point) } catch (_) {}
const goal = { isEnd: function () { climb(goal.isEnd); return true }, heuristic: function () { return 0 }, hasChanged: () => false, isValid: () => true }
try { await bot.pathfinder.goto(goal) } catch (_) {}
const listener = function () { climb(listener) }
bot.inventory.on('updateSlot', listener); bot.world.on('blockUpdate', listener)
await bot.waitForTicks(5)
bot.inventory.removeListener('updateSlot', listener); bot.world.removeListener('blockUpdate', listener)
return found
"""

GRAPH_WALK = """
const seen = new Set(), found = []
const queue = [[globalThis, 'globalThis']]
const bad = (v) => v._client || (v.pid && typeof v.exit === 'function') || (typeof v === 'function' && /^(require|dlopen|binding)$/.test(v.name)) || v.constructor?.name === 'Socket' || typeof v.NODE_PATH === 'string' || typeof v.PATH === 'string'
let t0 = Date.now()
for (let i = 0; i < queue.length && seen.size < 400000; i++) {
  if (Date.now() - t0 > 100) { await bot.waitForTicks(1); t0 = Date.now() }
  const [v, path] = queue[i]
  if (v === null || (typeof v !== 'object' && typeof v !== 'function') || seen.has(v)) continue
  seen.add(v)
  try { if (bad(v)) { found.push(path); continue } } catch (_) {}
  if (ArrayBuffer.isView(v) || (Array.isArray(v) && v.length > 500)) continue
  let keys = []
  try { keys = Reflect.ownKeys(v) } catch (_) { continue }
  for (const k of keys) {
    let d; try { d = Object.getOwnPropertyDescriptor(v, k) } catch (_) { continue }
    if (!d) continue
    let val = d.value
    if (d.get) { try { val = d.get.call(v) } catch (_) { continue } queue.push([d.get, path + '.get ' + String(k)]) }
    queue.push([val, path + '.' + String(k)])
  }
  try { queue.push([Object.getPrototypeOf(v), path + '.__proto__']) } catch (_) {}
}
return { walked: seen.size, found: found.slice(0, 5) }
"""


async def _returned(player, code):
    """What the code returns (saved through bot.save as JSON, the only way out of a run)."""
    events = await player.run(
        "const __r = await (async () => {\n%s\n})()\nbot.save(JSON.stringify(__r))" % code, timeout=120
    )
    assert errors(events) == [], errors(events)
    return json.loads(next(e[1]["onSave"] for e in events if e[0] == "onSave"))


async def test_stack_frames_do_not_hand_out_the_bot(shared):
    bad, other = shared
    assert await _returned(bad, STACK_FRAMES) == []
    await _bystander_ok(other)


async def test_host_prototypes_cannot_be_replaced(shared):
    bad, other = shared
    out = await _returned(bad, PROTOTYPES)
    assert out["replaced"] == []
    events = await bad.run(
        "await bot.waitForTicks(2)\nreturn bot.entity.position.offset(0, 1, 0).y"
    )  # the bot still works
    assert errors(events) == []
    await _bystander_ok(other)


async def test_caller_chains_do_not_reach_the_bot(shared):
    bad, _ = shared
    assert await _returned(bad, CALLER_CHAINS) == []


async def test_no_property_path_reaches_the_bot_process_or_require(shared):
    bad, _ = shared
    out = await _returned(bad, GRAPH_WALK)
    assert out["found"] == [] and out["walked"] > 10000, out


# Every own property of the agent's global object, enumerable or not (a hidden `env` would show).
GLOBAL_NAMES = """
return { names: Object.getOwnPropertyNames(globalThis), symbols: Object.getOwnPropertySymbols(globalThis).map(String) }
"""

# The language's built-ins: the own properties of a fresh, empty vm context's global object.
EMPTY_CONTEXT = r"""
const vm = require('vm')
const context = vm.createContext({}, { codeGeneration: { strings: false, wasm: false } })
console.log(JSON.stringify(vm.runInContext(
  '({ names: Object.getOwnPropertyNames(globalThis), symbols: Object.getOwnPropertySymbols(globalThis).map(String) })',
  context)))
"""


async def test_agent_globals_are_the_documented_names_only(shared):
    """The documented list (docs/security.md): the language's built-ins, sandbox_globals.json and
    the primitives of modules.json; nothing else, not even non-enumerable (no `env`, no `process`)."""
    bad, _ = shared
    found = await _returned(bad, GLOBAL_NAMES)
    builtins = run_node_script(EMPTY_CONTEXT)
    assert set(found["names"]) == set(builtins["names"]) | SANDBOX_NAMES | set(prim.functions())
    assert set(found["symbols"]) == set(builtins["symbols"])
    assert not {"env", "process", "require", "global", "module"} & set(found["names"])


async def test_env_is_nowhere_in_reach(shared):
    bad, _ = shared
    found = await _returned(
        bad,
        "return [typeof env, 'env' in globalThis, Reflect.has(globalThis, 'env'), typeof bot.env,"
        " typeof globalThis.process, Object.getOwnPropertyDescriptor(globalThis, 'env') === undefined]",
    )
    assert found == ["undefined", False, False, "undefined", "undefined", True]
