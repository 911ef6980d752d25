'use strict'
// One player: a mineflayer bot driven by JSON lines on stdin, answering on stdout.
//   usage: node --permission ... main.js '{"host": "127.0.0.1", "port": 25565, "username": "Ryn", "primitives": null, "clock": "real"}'
// The protocol is declared once, in bot_protocol.json (read by Python too: pillagerbench/players/
// bot_protocol.py): the settings above, the requests in (each op's arguments and answer: replies
// {"id", "ok", "result"|"error"}), the lines out besides replies (hb, spawned, ev, fatal) and the
// observation. A request is dispatched from it (protocol.js); the bot does not start when its settings or
// its handlers (OPS, RUNS, CUES below) differ from it (tests/players/test_bot_protocol.py).
const settings = JSON.parse(process.argv[2] || '{}')
const protocol = require('./protocol')
protocol.refuse(protocol.settingsProblems(settings))
const clock = require('../clock/game_clock')
clock.install(settings.clock) // before anything reads the time (game_clock.js)
require('./speedups').install() // cheaper equivalents of two library hot spots (speedups.js)
const readline = require('readline')

const out = (obj) => process.stdout.write(JSON.stringify(obj) + '\n')
const log = (...args) => process.stderr.write(args.join(' ') + '\n')

const heartbeat = clock.real.setInterval(() => out({ hb: 1 }), settings.heartbeatMs || 200)

const mineflayer = require('mineflayer')
const { pathfinder } = require('mineflayer-pathfinder')
const { plugin: tool } = require('mineflayer-tool')
const { plugin: collectBlock } = require('mineflayer-collectblock')
const { plugin: pvp } = require('mineflayer-pvp')
const { Vec3 } = require('vec3')
const { Run, isStop } = require('./run')
const { gate, within, clearLeftovers } = require('./gate')
const { waitTicks } = require('./ticks')
const { Observer } = require('./observe')
const { LagMeter } = require('./lag')
const watchdog = require('./watchdog')
const sandbox = require('./sandbox')
const primitives = require('./primitives')
const person = require('./person')
const view = require('./view')
const { seededRandom, seedOf } = require('../clock/random')

const CHAT_LIMIT = 25
const CHAT_WINDOW_TICKS = 100
const CHAT_PIECE = 256
const EVENT_BUFFER = 200

// settings.cue: connect only at the login op (a line on stdin, `Player.start`). A match launches its bots'
// processes all at once, so each loads its libraries and sets itself up meanwhile, and still logs them in
// one at a time. Any other line before it gets an error reply. Without it, at once.
const CUES = { login: (connect) => connect() } // the ops answered by the spawned line
function cued (connect) {
  if (!settings.cue) return connect()
  const rl = readline.createInterface({ input: process.stdin })
  let go = false
  rl.on('line', (line) => {
    if (go) return
    const { msg, op, error } = protocol.parse(line)
    if (op && protocol.answerOf(op) === 'spawned') { go = true; rl.close(); return CUES[op](connect) }
    out({ id: msg.id ?? null, ok: false, error: error || `op ${op}: not logged in yet (the first request is login)` })
  })
  rl.once('close', () => { if (!go) process.exit(0) }) // closed before its cue: nothing to play
}
const net = require('net')
const bot = mineflayer.createBot({
  host: settings.host || '127.0.0.1',
  port: settings.port,
  connect: (client) => cued(() => client.setSocket(net.connect(settings.port, settings.host || '127.0.0.1'))),
  username: settings.username,
  version: '1.16.5',
  auth: 'offline',
  checkTimeoutInterval: 3600 * 1000,
  hideErrors: true,
  logErrors: false
})
const lockstep = require('./lockstep')
lockstep.attach(bot) // clock=lockstep: this bot does the server's ticks
bot.loadPlugin(pathfinder)
// Upstream's bots had these too; agent code reaches them through the facade (sandbox.js).
bot.loadPlugin(tool)
bot.loadPlugin(collectBlock)
bot.loadPlugin(pvp)
gate(bot, () => current) // a stopped run's leftovers cannot act (gate.js)
if (settings.view) view.load(bot) // a person's player: its view's server made before the bot is hardened (view.js)
// The bots' writes are not batched (batch.js): a dig's finish and the next packet would then reach the
// server in one read, and flying-squid's asynchronous dig handler lets the next packet (a place against
// the block just dug) see the block before the dig has changed it (tests/server/test_fair_play.py).
if (process.env.PB_TRACE) { // packets received by name: count and bytes, logged at exit
  const got = {}
  bot._client.on('packet', (data, meta, buffer) => {
    const g = got[meta.name] || (got[meta.name] = [0, 0])
    g[0]++; g[1] += buffer ? buffer.length : 0
  })
  process.on('exit', () => log(`[trace] packets ${JSON.stringify(Object.entries(got).sort((a, b) => b[1][1] - a[1][1]).slice(0, 15))}`))
}
if (/\bsearch\b/.test(process.env.PB_TRACE || '')) require('./search_trace').install(log)

let mcData = null
let observer = null
let lag = null // physics-tick lag of this process (lag.js)
let current = null // the active Run
const buffered = [] // events that happened between runs, delivered with the next run
let chatCount = 0
// Position packets the server forced on this bot (mineflayer's 'forcedMove': a teleport, a correction),
// and how many of them the last settle had seen: a settle waits for a new one, so a bot that already
// stands at the teleport's target does not answer before the teleport (its look) has arrived.
let forcedMoves = 0
let settledMoves = 0
bot.on('forcedMove', () => { forcedMoves++ })
const pendingEcho = [] // our own chat lines not yet seen back from the server

// ---- events --------------------------------------------------------------------------------
function emit (type, value) {
  let data
  try { data = observer.observe() } catch (err) { data = {} }
  if (type !== 'observe') data[type] = value
  const ev = [type, data]
  if (current) out({ ev, run: current.id })
  else {
    buffered.push(ev)
    if (buffered.length > EVENT_BUFFER) buffered.shift()
  }
}

function reportError (err) {
  if (isStop(err)) return
  emit('onError', sandbox.describeError(err, current ? current.code : ''))
}

// ---- chat with upstream's rate limit ---------------------------------------------------------
function chat (message) {
  const text = String(message)
  const pieces = text.length === 0 ? [''] : text.match(new RegExp(`[^]{1,${CHAT_PIECE}}`, 'g'))
  if (chatCount + pieces.length > CHAT_LIMIT) {
    throw new Error(`Too many chats in short succession! At most ${CHAT_LIMIT} chat messages per ${CHAT_WINDOW_TICKS} ticks.`)
  }
  chatCount += pieces.length
  for (const piece of pieces) {
    if (!piece.startsWith('/')) pendingEcho.push({ line: `<${bot.username}> ${piece}`, at: Date.now() })
    bot.chat(piece)
  }
}

function waitEchoes (maxMs) {
  const deadline = Date.now() + maxMs
  return new Promise(resolve => {
    const check = () => {
      while (pendingEcho.length && Date.now() - pendingEcho[0].at > 3000) pendingEcho.shift()
      if (pendingEcho.length === 0 || Date.now() >= deadline) return resolve()
      setTimeout(check, 5)
    }
    check()
  })
}

// ---- runs ------------------------------------------------------------------------------------
// Stop whatever the bot is doing on behalf of the run, then settle the run.
function halt (run, reason) {
  if (!run.active) return
  try { bot.pvp.forceStop() } catch (_) {}
  try { bot.collectBlock.cancelTask().catch(() => {}) } catch (_) {}
  try { bot.pathfinder.stop(); bot.pathfinder.setGoal(null) } catch (_) {}
  try { if (bot.targetDigBlock) bot.stopDigging() } catch (_) {}
  try { bot.clearControlStates() } catch (_) {}
  try { if (bot.currentWindow) bot.closeWindow(bot.currentWindow) } catch (_) {}
  try { bot.deactivateItem() } catch (_) {}
  run.stop(reason)
}

async function doRun (msg) {
  if (current) halt(current, 'Stopped: another run started')
  current = null
  clearLeftovers(bot) // no dig of an earlier run is left for this one to cancel (gate.js)
  const code = typeof msg.code === 'string' ? msg.code : ''
  const run = new Run(msg.id, { startTick: observer.ticks })
  lockstep.busy(bot)
  run.code = code
  observer.runStartTick = observer.ticks
  current = run
  for (const ev of buffered.splice(0)) out({ ev, run: run.id })
  run.listen(bot, 'physicsTick', watchdog.watchdog(bot, () => log('[watchdog] the pathfinder stood with its goal unreached and no path for 5 s: goal set again')))
  let timer = null
  if (msg.timeout) {
    timer = setTimeout(() => {
      if (!run.active) return
      emit('onError', `Timeout: the code ran longer than ${msg.timeout} s and was stopped`)
      run.timedOut = true
      halt(run, 'Stopped: time limit reached')
    }, msg.timeout * 1000)
  }
  const ctx = {
    bot,
    run,
    mcData,
    Vec3,
    goals: require('mineflayer-pathfinder').goals,
    observer,
    chat: (m) => { run.check(); chat(m) },
    save: (name) => { run.check(); emit('onSave', name) }
  }
  try {
    const prims = primitives.build(ctx, settings.primitives || null)
    const context = sandbox.createContext({
      bot, run, mcData, Vec3, primitives: prims, chat: ctx.chat, save: ctx.save, report: reportError,
      log: (level, text) => log(`[agent ${level}] ${text.slice(0, 2000)}`),
      random: Math.random
    })
    const done = within(run, () => sandbox.execute(context, code)) // its packets carry the run (gate.js)
    await Promise.race([done, run.stopped])
  } catch (err) {
    if (!isStop(err) && run.active) {
      await waitEchoes(500) // chats sent before the error come first, as they happened
      emit('onError', sandbox.describeError(err, code))
    }
  }
  clearTimeout(timer)
  const stopped = !run.active
  if (process.env.PB_TRACE) log(`[trace] run settled ${Date.now() % 100000}`)
  halt(run, 'Stopped: the code has finished')
  await waitEchoes(stopped ? 100 : 1000)
  if (process.env.PB_TRACE) log(`[trace] echoes ${Date.now() % 100000}`)
  emit('observe')
  current = null
  lockstep.idle(bot) // before the answer: the team's next step starts at this tick
  if (process.env.PB_TRACE) log(`[trace] run reply ${Date.now() % 100000}`)
  out({ id: msg.id, ok: true, result: { stopped: stopped && !run.timedOut, tick: lockstep.tick() } })
}

// ---- requests --------------------------------------------------------------------------------
const OPS = {
  ping: async () => 'pong',
  // What Node's permission model lets this process do (all false but fs.read of our own modules).
  permissions: async () => {
    const has = (scope, ref) => Boolean(process.permission && process.permission.has(scope, ref))
    return { enabled: Boolean(process.permission), fsWrite: has('fs.write'), fsReadRoot: has('fs.read', '/etc/passwd'), childProcess: has('child'), worker: has('worker'), addons: has('addon') }
  },
  memory: async ({ gc }) => {
    if (gc && global.gc) global.gc()
    const m = process.memoryUsage()
    return Object.fromEntries(Object.entries(m).map(([k, v]) => [k, Math.round(v / 2 ** 20 * 10) / 10]))
  },
  stop: async () => {
    if (process.env.PB_TRACE) log(`[trace] stop received ${Date.now() % 100000}`)
    if (current) halt(current, 'Stopped')
    return true
  },
  observe: async () => observer.observe(),
  // Physics-tick lag since the last `lag` request with reset: true (see lag.js).
  lag: async ({ reset }) => {
    const result = lag.read()
    if (reset) lag.reset()
    return result
  },
  clear: async ({ seed }) => {
    if (Number.isInteger(seed)) Math.random = seededRandom(seedOf(seed, bot.username)) // this episode's chance
    buffered.length = 0
    pendingEcho.length = 0
    observer.clear()
    chatCount = 0
    return true
  },
  // equipment: [head, chest, legs, feet, mainhand, offhand] names or null
  equip: async ({ equipment }) => {
    const dests = ['head', 'torso', 'legs', 'feet', 'hand', 'off-hand']
    const list = Array.isArray(equipment) ? equipment : dests.map(d => (equipment || {})[d] ?? null)
    for (let i = 0; i < dests.length; i++) {
      const name = list[i]
      if (!name) continue
      const item = bot.inventory.items().find(it => it.name === name)
      if (!item) throw new Error(`cannot equip ${name}: not in the inventory`)
      await bot.equip(item, dests[i])
    }
    return true
  },
  // A person's key or mouse input, inside the current run (its packets pass the gate as the run's own).
  act: async ({ input }) => {
    if (!current || !current.active) throw new Error('the game is not on: nothing you do acts now')
    return within(current, () => person.act(bot, input))
  },
  hud: async () => person.hud(bot),
  view: async () => view.view(),
  // Wait until the server's teleport since the last settle has arrived, the bot stands near `pos`
  // and the ground under it is loaded.
  settle: async ({ pos, timeout = 5 }) => {
    const deadline = Date.now() + timeout * 1000
    const target = pos ? new Vec3(pos[0], pos[1], pos[2]) : null
    while (Date.now() < deadline) {
      const here = bot.entity.position
      const below = bot.blockAt(here.offset(0, -1, 0))
      if (forcedMoves > settledMoves && (!target || here.distanceTo(target) < 1.5) && below) {
        settledMoves = forcedMoves
        return true
      }
      await waitTicks(bot, 1)
    }
    const p = bot.entity.position
    return { x: p.x, y: p.y, z: p.z }
  }
}

// The ops that answer when a run ends (their events first): doRun replies itself.
const RUNS = { run: doRun }
protocol.refuse(protocol.undeclared({ reply: OPS, run: RUNS, spawned: CUES }))

// How each kind of declared answer is given (bot_protocol.json's `answer`).
const ANSWER = {
  reply: async (op, msg) => {
    try {
      out({ id: msg.id, ok: true, result: (await OPS[op](msg)) ?? null })
    } catch (err) {
      out({ id: msg.id, ok: false, error: err && err.message ? err.message : String(err) })
    }
  },
  run: (op, msg) => RUNS[op](msg).catch(err => out({ id: msg.id, ok: false, error: String(err && err.stack ? err.stack : err) })),
  spawned: (op, msg) => out({ id: msg.id ?? null, ok: false, error: `op ${op}: already logged in` })
}

function startProtocol () {
  const rl = readline.createInterface({ input: process.stdin })
  rl.on('line', (line) => clock.atBoundary(() => handle(line)))
  function handle (line) {
    const { msg, op, error } = protocol.parse(line)
    if (error) return out({ id: msg.id ?? null, ok: false, error })
    return ANSWER[protocol.answerOf(op)](op, msg)
  }
  rl.on('close', () => { try { bot.quit() } catch (_) {} clock.real.setTimeout(() => process.exit(0), 100) })
}

bot.once('spawn', async () => {
  mcData = require('minecraft-data')(bot.version)
  observer = new Observer(bot)
  lag = new LagMeter(bot)
  bot.pathfinder.setMovements(sandbox.defaultMovements(bot))
  watchdog.remember(bot)
  // collectblock and pvp set their own Movements on every call (stock ones dig and build towers):
  // give them ours, so the pathfinder's rules stay the same whoever asks
  // (collectblock skips blocks its Movements may not break, so its own may dig, as upstream's did)
  bot.collectBlock.movements = Object.assign(sandbox.defaultMovements(bot), { canDig: true })
  bot.pvp.movements = sandbox.defaultMovements(bot)
  bot.pathfinder.thinkTimeout = 2000
  // ms of path search per tick. 7 with the cheaper block lookup of movements.js visits about as many
  // nodes per tick as 20 did with the stock one (docs/performance.md): the same searches for a third
  // of the CPU, and the bot answers stop() quickly. On the lockstep clock: 140 nodes (game_clock.js).
  bot.pathfinder.tickTimeout = 7
  bot.on('physicsTick', () => { if (observer.ticks % CHAT_WINDOW_TICKS === 0) chatCount = 0 })
  bot.on('messagestr', (message, position) => {
    if (position === 'game_info') return
    const i = pendingEcho.findIndex(p => p.line === message)
    if (i >= 0) pendingEcho.splice(0, i + 1)
    emit('onChat', message)
  })
  bot.on('mount', () => { try { bot.dismount() } catch (_) {} })
  if (process.env.PB_TRACE) bot.on('path_update', (r) => log(`[trace] path ${r.status} ${Math.round(r.time)} ms ${r.visitedNodes} nodes ${r.path.length} long`))
  try { await bot.waitForChunksToLoad() } catch (_) {}
  sandbox.harden(bot)
  const p = bot.entity.position
  out({ spawned: { username: bot.username, position: { x: p.x, y: p.y, z: p.z } } })
  startProtocol()
})

process.on('unhandledRejection', (err) => {
  if (isStop(err)) return
  reportError(err)
})
process.on('uncaughtException', (err) => {
  if (isStop(err)) return
  log(`[bot] uncaught: ${err && err.stack ? err.stack : err}`)
  if (observer) reportError(err)
})

bot.on('kicked', (reason) => { out({ fatal: `kicked: ${typeof reason === 'string' ? reason : JSON.stringify(reason)}` }); process.exit(3) })
bot.on('end', (reason) => { out({ fatal: `disconnected: ${reason}` }); clock.real.clearInterval(heartbeat); process.exit(3) })
bot.on('error', (err) => log(`[bot] error: ${err && err.message ? err.message : err}`))
