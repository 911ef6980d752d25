"""The lists Python and JavaScript share are declared once, on the JavaScript side, and Python reads them:
the primitives (js/bot/primitives/modules.json), the sandbox's globals (js/bot/sandbox_globals.json) and
what the server can smelt (js/server/smelting.json). Each test asks Node what the JavaScript actually
does (what each module's make(ctx) returns, what a sandbox context holds, the server's SMELTING table)
and compares it with what Python uses."""

from __future__ import annotations

from pillagerbench.agents.code import SANDBOX_NAMES
from pillagerbench.players import primitives as prim
from pillagerbench.teams.random_team import SMELTABLE
from tests.support.node_script import run_node_script

# every file of js/bot/primitives that exports a module ({name, make}), with the functions its
# make(ctx) returns; what index.js loads and what build(ctx) gives a run
PRIMITIVES = r"""
const fs = require('fs')
const dir = process.argv[1] + '/bot/primitives/'
const index = require(dir + 'index.js')
const ctx = { bot: {}, run: {}, mcData: {} }
const files = {}
for (const f of fs.readdirSync(dir).filter(f => f.endsWith('.js') && f !== 'index.js')) {
  const mod = require(dir + f)
  if (typeof mod.make === 'function') files[f] = { name: mod.name, functions: Object.keys(mod.make(ctx)) }
}
console.log(JSON.stringify({ files, loaded: index.MODULE_NAMES, built: Object.keys(index.build(ctx)) }))
"""


def test_primitives_are_what_the_modules_make():
    js = run_node_script(PRIMITIVES)
    made = {m["name"]: m["functions"] for m in js["files"].values()}
    assert all(f == f"{m['name']}.js" for f, m in js["files"].items()), js["files"]
    assert {m: sorted(fs) for m, fs in made.items()} == {m: sorted(fs) for m, fs in prim.MODULES.items()}
    assert js["loaded"] == list(prim.MODULES)  # index.js loads the modules Python lists, in its order
    assert sorted(js["built"]) == sorted(prim.functions())
    assert len(prim.functions()) == len(set(prim.functions()))  # no function in two modules


# a sandbox context made with stand-ins: the names agent code finds in it besides the language's built-ins
# (those of an empty context), enumerable or not
SANDBOX = r"""
const vm = require('vm')
const { createContext } = require(process.argv[1] + '/bot/sandbox.js')
const context = createContext({
  bot: {}, run: { timers: new Set(), intervals: new Set() }, mcData: {}, Vec3: require('vec3').Vec3,
  primitives: { somePrimitive () {} }, chat () {}, save () {}, report () {}, log () {}
})
const builtins = vm.runInContext('Object.getOwnPropertyNames(globalThis)', vm.createContext({}))
const names = vm.runInContext('Object.getOwnPropertyNames(globalThis)', context)  // non-enumerable ones too
const missing = vm.runInContext('Object.keys(globalThis).filter(n => globalThis[n] === undefined)', context)
console.log(JSON.stringify({ names, builtins, missing }))
"""


def test_sandbox_names_are_what_the_sandbox_gives():
    js = run_node_script(SANDBOX)
    assert js["missing"] == []
    assert "somePrimitive" in js["names"]
    assert set(js["names"]) == set(js["builtins"]) | SANDBOX_NAMES | {"somePrimitive"}


SMELTING = r"""
const { SMELTING } = require(process.argv[1] + '/server/tables.js')
const registry = require('minecraft-data')('1.16.5')
console.log(JSON.stringify({ inputs: Object.keys(SMELTING), unknown: Object.entries(SMELTING).flat().filter(n => !registry.itemsByName[n]) }))
"""


def test_random_smelts_only_what_the_server_can_smelt():
    js = run_node_script(SMELTING)
    assert js["unknown"] == []
    assert SMELTABLE == set(js["inputs"])
    assert not SMELTABLE & {"clay_ball", "wet_sponge"}  # listed by hand before; the server cannot smelt them
