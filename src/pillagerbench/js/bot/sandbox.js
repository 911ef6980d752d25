'use strict'
// The sandbox: agent code runs in a fresh `vm` context per run holding only the primitives, a
// documented subset of the mineflayer bot (a facade), Vec3, mcData, the pathfinder goals, Movements
// options and timers/listeners owned by the run. Code generation from strings is off inside the
// context and the host realm's function constructors are blocked (harden), so `x.constructor.constructor`
// leads nowhere; the process also runs under Node's permission model (see main.js).
const vm = require('vm')
const clock = require('../clock/game_clock')
const { goals, Movements } = require('mineflayer-pathfinder')
const { isStop } = require('./run')
const { waitTicks } = require('./ticks')
const { lockPrototypes } = require('./lockdown')
const { defaultMovements } = require('./movements')

// The names agent code may use without defining them (besides the primitives and the language's
// built-ins), declared once: Python's code check reads the same file (agents/code.py).
const GLOBALS = require('./sandbox_globals.json')

const FILENAME = 'agent.js'
const SYNC_TIMEOUT_MS = 1000

// The engine's constructors whose prototypes host objects inherit from (locked by harden).
const INTRINSICS = [Object, Function, Array, Promise, Error, EvalError, RangeError, ReferenceError, SyntaxError,
  TypeError, URIError, Map, Set, WeakMap, WeakSet, Date, RegExp, String, Number, Boolean, Symbol, BigInt,
  ArrayBuffer, DataView, Uint8Array, Int8Array, Uint16Array, Int16Array, Uint32Array, Int32Array, Float32Array,
  Float64Array, BigInt64Array, BigUint64Array, [][Symbol.iterator](), new Map().entries(), new Set().values(),
  ''[Symbol.iterator](), function * () {}, async function () {}, async function * () {}]

// Block the host realm's Function constructors (reached as someHostFunction.constructor), then
// lock the prototypes of the host objects agent code can reach (lockdown.js). `bot` is the logged-in
// bot (its world, entity, inventory, blocks and items are the roots).
function harden (bot) {
  const protos = [Function.prototype, Object.getPrototypeOf(async function () {}),
    Object.getPrototypeOf(function * () {}), Object.getPrototypeOf(async function * () {})]
  for (const proto of protos) {
    const name = proto.constructor.name
    const blocked = function () { throw new EvalError('Code generation is not available to agent code') }
    Object.defineProperty(blocked, 'name', { value: name })
    Object.defineProperty(proto, 'constructor', { value: blocked, writable: false, configurable: false, enumerable: false })
  }
  try {
    Object.defineProperty(Error, 'prepareStackTrace', { value: undefined, writable: false, configurable: false })
  } catch (_) {}
  if (!bot) return
  const Item = require('prismarine-item')(bot.registry)
  const Block = require('prismarine-block')(bot.registry)
  const roots = [...INTRINSICS, bot.entity, bot.world, bot.inventory, bot.players, bot.entities, bot.game,
    bot.blockAt(bot.entity.position), new Item(1, 1), Block.fromStateId(1, 0), require('vec3').Vec3, goals, Movements,
    new Movements(bot), bot.registry]
  lockPrototypes(roots)
}

const MOVEMENT_OPTIONS = ['canDig', 'digCost', 'placeCost', 'allow1by1towers', 'allowFreeMotion', 'allowParkour',
  'allowSprinting', 'dontCreateFlow', 'dontMineUnderFallingBlock', 'maxDropDown', 'infiniteLiquidDropdownDistance',
  'liquidCost', 'entityCost', 'canOpenDoors', 'allowEntityDetection']

// The `bot` agent code sees. Every method checks that the run is still active; async ones settle
// when the run stops.
function makeFacade (bot, run, { chat, save, report }) {
  const sync = (fn) => function (...args) { run.check(); return fn(...args) }
  const async = (fn) => async function (...args) { run.check(); return run.race(fn(...args)) }
  const wrapListener = (listener) => guardListener(run, report, listener)
  const owned = new Map() // agent listener -> [event, wrapped]

  const pathfinder = pathfinderFacade(bot, run, sync)
  const { collectBlock, tool, pvp } = pluginFacades(bot, sync, async)

  const facade = {
    get username () { return bot.username },
    get entity () { return bot.entity },
    get entities () { return bot.entities },
    get players () { return bot.players },
    get health () { return bot.health },
    get food () { return bot.food },
    get foodSaturation () { return bot.foodSaturation },
    get oxygenLevel () { return bot.oxygenLevel },
    get heldItem () { return bot.heldItem },
    get inventory () { return bot.inventory },
    get currentWindow () { return bot.currentWindow },
    get game () { return bot.game },
    get time () { return bot.time },
    get version () { return bot.version },
    get world () { return bot.world },
    get quickBarSlot () { return bot.quickBarSlot },
    get targetDigBlock () { return bot.targetDigBlock },
    get experience () { return bot.experience },
    get controlState () { return { ...bot.controlState } },
    pathfinder,
    collectBlock,
    tool,
    pvp,
    ...botQueries(bot, sync),
    chat: sync((m) => chat(m)),
    save: sync((name) => save(String(name))),
    ...botActions(bot, async),
    on: sync((event, listener) => {
      const w = wrapListener(listener); owned.set(listener, [event, w]); run.listen(bot, String(event), w); return facade
    }),
    once: sync((event, listener) => {
      const w = wrapListener((...a) => { run.unlisten(bot, String(event), w); owned.delete(listener); return listener(...a) })
      owned.set(listener, [event, w]); run.listen(bot, String(event), w); return facade
    }),
    removeListener: (event, listener) => {
      const o = owned.get(listener)
      if (o) { run.unlisten(bot, o[0], o[1]); owned.delete(listener) }
      return facade
    }
  }
  facade.addListener = facade.on
  facade.off = facade.removeListener
  return facade
}

// An agent's listener, called only while the run is active; what it throws (or rejects with) is reported.
function guardListener (run, report, listener) {
  return function (...args) {
    if (!run.active) return
    try {
      const r = listener(...args)
      if (r && typeof r.catch === 'function') r.catch(err => { if (!isStop(err)) report(err) })
    } catch (err) { if (!isStop(err)) report(err) }
  }
}

function pathfinderFacade (bot, run, sync) {
  return {
    goto: async (goal) => run.race(bot.pathfinder.goto(goal)),
    setGoal: sync((goal, dynamic = false) => bot.pathfinder.setGoal(goal, dynamic)),
    stop: sync(() => bot.pathfinder.stop()),
    isMoving: () => bot.pathfinder.isMoving(),
    isMining: () => bot.pathfinder.isMining(),
    isBuilding: () => bot.pathfinder.isBuilding(),
    get goal () { return bot.pathfinder.goal },
    setMovements: sync((options = {}) => {
      const m = defaultMovements(bot)
      for (const k of MOVEMENT_OPTIONS) if (options[k] !== undefined) m[k] = options[k]
      bot.pathfinder.setMovements(m)
    })
  }
}

// Upstream's plugins (mineflayer-collectblock, mineflayer-tool, mineflayer-pvp), behind the same
// run checks; stopping a run also cancels their tasks (main.js halt).
function pluginFacades (bot, sync, async) {
  const collectBlock = {
    collect: async((target, options = {}) => bot.collectBlock.collect(target, collectOptions(options))),
    cancelTask: async(() => bot.collectBlock.cancelTask())
  }
  const tool = {
    equipForBlock: async((block, options = {}) => bot.tool.equipForBlock(block, toolOptions(options)))
  }
  const pvp = {
    attack: async((entity) => bot.pvp.attack(entity)),
    stop: async(() => bot.pvp.stop()),
    forceStop: sync(() => bot.pvp.forceStop()),
    get target () { return bot.pvp.target },
    get followRange () { return bot.pvp.followRange },
    get attackRange () { return bot.pvp.attackRange }
  }
  return { collectBlock, tool, pvp }
}

// The facade's methods that ask the bot (and its synchronous acts), each behind sync's run check.
function botQueries (bot, sync) {
  return {
    blockAt: sync((p, extra) => bot.blockAt(p, extra)),
    findBlock: sync((o) => bot.findBlock(o)),
    findBlocks: sync((o) => bot.findBlocks(o)),
    nearestEntity: sync((f) => bot.nearestEntity(f)),
    canSeeBlock: sync((b) => bot.canSeeBlock(b)),
    canDigBlock: sync((b) => bot.canDigBlock(b)),
    digTime: sync((b) => bot.digTime(b)),
    blockAtCursor: sync((d) => bot.blockAtCursor(d)),
    entityAtCursor: sync((d) => bot.entityAtCursor(d)),
    recipesFor: sync((...a) => bot.recipesFor(...a)),
    recipesAll: sync((...a) => bot.recipesAll(...a)),
    setControlState: sync((c, s) => bot.setControlState(c, s)),
    getControlState: sync((c) => bot.getControlState(c)),
    clearControlStates: sync(() => bot.clearControlStates()),
    setQuickBarSlot: sync((s) => bot.setQuickBarSlot(s)),
    attack: sync((e) => bot.attack(e)),
    swingArm: sync((...a) => bot.swingArm(...a)),
    useOn: sync((e) => bot.useOn(e)),
    stopDigging: sync(() => bot.stopDigging()),
    deactivateItem: sync(() => bot.deactivateItem()),
    closeWindow: sync((w) => bot.closeWindow(w)),
    inventoryUsed: sync(() => bot.inventory.slots.slice(9, 45).filter(Boolean).length)
  }
}

// The facade's acts that take time, each behind async's run check and settling when the run stops.
function botActions (bot, async) {
  return {
    waitForTicks: async((n) => waitTicks(bot, n)),
    waitForChunksToLoad: async(() => bot.waitForChunksToLoad()),
    equip: async((i, d) => bot.equip(i, d)),
    unequip: async((d) => bot.unequip(d)),
    toss: async((t, m, c) => bot.toss(t, m, c)),
    tossStack: async((i) => bot.tossStack(i)),
    dig: async((b, f, d) => bot.dig(b, f, d)),
    placeBlock: async((b, f) => bot.placeBlock(b, f)),
    activateBlock: async((b, d, c) => bot.activateBlock(b, d, c)),
    activateItem: async((o) => bot.activateItem(o)),
    activateEntity: async((e) => bot.activateEntity(e)),
    consume: async(() => bot.consume()),
    lookAt: async((p, f) => bot.lookAt(p, f)),
    look: async((y, p, f) => bot.look(y, p, f)),
    openContainer: async((b) => bot.openContainer(b)),
    openChest: async((b) => bot.openContainer(b)),
    openFurnace: async((b) => bot.openFurnace(b)),
    craft: async((r, c, t) => bot.craft(r, c, t))
  }
}

// The options agent code may give the plugins: known keys only, plain values.
function collectOptions (o) {
  const out = {}
  if (o && typeof o === 'object') {
    if (o.ignoreNoPath !== undefined) out.ignoreNoPath = Boolean(o.ignoreNoPath)
    if (o.append !== undefined) out.append = Boolean(o.append)
    if (Array.isArray(o.chestLocations)) out.chestLocations = o.chestLocations.slice()
    if (typeof o.itemFilter === 'function') out.itemFilter = o.itemFilter
  }
  return out
}

function toolOptions (o) {
  const out = {}
  if (o && typeof o === 'object') {
    if (o.requireHarvest !== undefined) out.requireHarvest = Boolean(o.requireHarvest)
    if (o.getFromChest !== undefined) out.getFromChest = Boolean(o.getFromChest)
    if (Number.isFinite(o.maxTools)) out.maxTools = o.maxTools
  }
  return out
}

// A fresh context for one run. `names`: primitive functions; `log`: console output.
function createContext ({ bot, run, mcData, Vec3, primitives, chat, save, report, log, random }) {
  const trackTimer = (set, clear, registry) => (fn, ms, ...args) => {
    run.check()
    if (typeof fn !== 'function') throw new TypeError('timer callback must be a function')
    const id = set(() => {
      if (registry === run.timers) registry.delete(id)
      if (!run.active) return
      try {
        const r = fn(...args)
        if (r && typeof r.catch === 'function') r.catch(err => { if (!isStop(err)) report(err) })
      } catch (err) { if (!isStop(err)) report(err) }
    }, ms)
    registry.add(id)
    return id
  }
  const clearTimer = (clear, registry) => (id) => { if (registry.has(id)) { registry.delete(id); clear(id) } }
  const print = (level) => (...args) => log(level, args.map(a => typeof a === 'string' ? a : safeString(a)).join(' '))
  const provided = {
    bot: makeFacade(bot, run, { chat, save, report }),
    mcData,
    Vec3,
    Movements: function Movements () { return Object.fromEntries(MOVEMENT_OPTIONS.map(k => [k, undefined])) },
    setTimeout: trackTimer(setTimeout, clearTimeout, run.timers),
    clearTimeout: clearTimer(clearTimeout, run.timers),
    setInterval: trackTimer(setInterval, clearInterval, run.intervals),
    clearInterval: clearTimer(clearInterval, run.intervals),
    console: { log: print('log'), info: print('info'), warn: print('warn'), error: print('error'), debug: print('debug') },
    ...goals
  }
  const sandbox = {}
  for (const name of GLOBALS) {
    if (!(name in provided)) throw new Error(`sandbox_globals.json names ${name}, which the sandbox does not provide`)
    sandbox[name] = provided[name]
  }
  Object.assign(sandbox, primitives)
  const context = vm.createContext(sandbox, { name: 'agent', codeGeneration: { strings: false, wasm: false } })
  LOCK_STACK_TRACES.runInContext(context)
  GAME_TIME_AND_CHANCE.runInContext(context)(clock.lockstep ? () => Date.now() : null, random || Math.random)
  return context
}

// The context's own Date and Math are its realm's, not the host's: on the lockstep clock its `Date`
// reads game time as the host's does (js/clock/game_clock.js), and its `Math.random` draws from the
// bot's seeded chance (js/clock/random.js), so agent code too plays the same game from the same seed.
const GAME_TIME_AND_CHANCE = new vm.Script(`(function (now, random) {
  Math.random = () => random()
  if (now === null) return
  const WallDate = Date
  const GameDate = function Date (...args) {
    if (!new.target) return new WallDate(now()).toString()
    return args.length ? new WallDate(...args) : new WallDate(now())
  }
  Object.setPrototypeOf(GameDate, WallDate)
  GameDate.prototype = WallDate.prototype
  GameDate.now = () => now()
  globalThis.Date = GameDate
})`)

// Node formats a stack trace with the `Error.prepareStackTrace` of the realm that made the error.
// Set in the agent's realm, it would receive V8's call sites, and `callSite.getThis()` on a frame
// of mineflayer's (sloppy-mode) code returns its receiver: the bot itself, with its `_client`.
// So the context's `Error` binding and its `prepareStackTrace` are made read-only.
const LOCK_STACK_TRACES = new vm.Script(`
Object.defineProperty(Error, 'prepareStackTrace', { value: undefined, writable: false, configurable: false })
Object.defineProperty(globalThis, 'Error', { value: Error, writable: false, configurable: false, enumerable: false })
`)

function safeString (v) {
  try { return JSON.stringify(v) ?? String(v) } catch (_) { return String(v) }
}

// Compile and start the code; returns the promise of its completion. Throws SyntaxError or the
// vm timeout synchronously.
function execute (context, code) {
  const script = new vm.Script(`(async () => {\n${code}\n})()`, { filename: FILENAME, lineOffset: -1 })
  return script.runInContext(context, { timeout: SYNC_TIMEOUT_MS, breakOnSigint: false })
}

// An error message that points at the line of the agent's code.
function describeError (err, code) {
  let text
  if (err && typeof err === 'object' && 'message' in err) text = `${err.name || 'Error'}: ${err.message}`
  else text = `Error: ${safeString(err)}`
  if (/Script execution timed out/.test(text)) {
    return `Error: the code ran for more than ${SYNC_TIMEOUT_MS / 1000} s without pausing (an endless loop?) and was stopped`
  }
  const stack = err && typeof err === 'object' && typeof err.stack === 'string' ? err.stack : ''
  const m = stack.match(new RegExp(FILENAME.replace('.', '\\.') + ':(\\d+)'))
  if (m) {
    const lines = code.split('\n')
    const n = Number(m[1])
    if (n >= 1 && n <= lines.length) text += `\nat line ${n}: ${lines[n - 1].trim()}`
  }
  return text
}

module.exports = { harden, createContext, execute, describeError, defaultMovements, SYNC_TIMEOUT_MS }
