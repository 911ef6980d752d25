'use strict'
// The control primitives: one module per file (the function) with its documentation for LLMs in the
// .md file of the same name. `build(ctx, allowed)` makes the functions for one run.
// modules.json lists the modules (in this order) and the functions each one's make(ctx) returns;
// Python reads the same file (players/primitives.py), tests/players/test_shared_lists.py checks both.
const MODULES = Object.keys(require('./modules.json')).map(name => require('./' + name))

// allowed: null (all) or a list of module names ("farm") and/or function names ("milkCow").
function build (ctx, allowed = null) {
  const out = {}
  const want = allowed ? new Set(allowed) : null
  for (const mod of MODULES) {
    const fns = mod.make(ctx)
    for (const [fname, fn] of Object.entries(fns)) {
      if (!want || want.has(mod.name) || want.has(fname)) out[fname] = fn
    }
  }
  return out
}

module.exports = { build, MODULE_NAMES: MODULES.map(m => m.name) }
