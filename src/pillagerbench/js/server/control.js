'use strict'
// The control channel: JSON lines on stdin -> replies on stdout, plus pushed events.
//   request: {"id": 7, "op": "set_block", "args": {"pos": [0, 4, 0], "block": "chest"}}
//   reply:   {"id": 7, "ok": true, "result": ...}  or  {"id": 7, "ok": false, "error": "unknown block 'chst' ..."}
//   event:   {"event": "block_dug", ...}
// The game master and the arena builder use only this. Every op validates its input; a bad request
// gets an error reply and never affects players.
// The ops are declared once, in control_ops.json (each op's arguments and answer, read by Python too:
// pillagerbench/server/seams.py). A request is dispatched from that declaration: an undeclared op or
// argument, a missing one or a scalar of another type, is refused before its handler runs; the handlers below are the
// declared ops exactly (checked when this module loads; tests/server/test_control_ops.py).
const { Vec3 } = require('vec3')
const { ControlError, toPos, toBlockPos, stateIdOf, itemByName, blockByName } = require('./util')
const { PICKUP } = require('./tables')
const DECLARED = require('./control_ops.json').ops
const clock = require('../clock/game_clock')

function playerNamed (serv, name) {
  const p = serv.players.find(pl => pl.username === name)
  if (!p) throw new ControlError(`no player named ${JSON.stringify(name)} (online: ${serv.players.map(pl => pl.username).join(', ') || 'none'})`)
  return p
}

const GAME_MODES = { survival: 0, creative: 1, adventure: 2, spectator: 3 }

// op name -> async (serv, args) => result
const OPS = {
  ping: async () => 'pong',
  status: async (serv) => ({ players: serv.players.map(p => p.username), tps: serv.pb.tps, tick: serv.tickCount, entities: Object.keys(serv.entities).length }),
  get_block: async (serv, { pos }) => serv.pb.describeBlock(toBlockPos(pos)),
  set_block: async (serv, { pos, block, properties }) => {
    await serv.pb.setBlockQuiet(toBlockPos(pos), stateIdOf(serv.registry, block, properties || {}))
    return true
  },
  // blocks: [[x, y, z, name, {props}?], ...] — validated first, then applied
  set_blocks: async (serv, { blocks }) => {
    if (!Array.isArray(blocks)) throw new ControlError('blocks must be a list of [x, y, z, name, properties?]')
    const edits = blocks.map((b, i) => {
      if (!Array.isArray(b) || b.length < 4) throw new ControlError(`blocks[${i}] must be [x, y, z, name, properties?]`)
      return [toBlockPos(b.slice(0, 3), `blocks[${i}]`), stateIdOf(serv.registry, b[3], b[4] || {})]
    })
    await Promise.all(edits.map(([p, s]) => serv.pb.setBlockQuiet(p, s)))
    return edits.length
  },
  fill: async (serv, { from, to, block, properties }) => serv.pb.fill(from, to, block, properties || {}),
  // Non-air blocks in a box, as [x, y, z, name, props]
  scan: async (serv, { from, to }) => {
    const a = toBlockPos(from, 'from'); const b = toBlockPos(to, 'to')
    const vol = (Math.abs(a.x - b.x) + 1) * (Math.abs(a.y - b.y) + 1) * (Math.abs(a.z - b.z) + 1)
    if (vol > 200000) throw new ControlError(`scan volume ${vol} is larger than 200000 blocks`)
    const out = []
    for (let x = Math.min(a.x, b.x); x <= Math.max(a.x, b.x); x++) {
      for (let y = Math.min(a.y, b.y); y <= Math.max(a.y, b.y); y++) {
        for (let z = Math.min(a.z, b.z); z <= Math.max(a.z, b.z); z++) {
          const blk = await serv.overworld.getBlock(a.clone().set(x, y, z))
          if (blk.name !== 'air') out.push([x, y, z, blk.name, blk.getProperties ? blk.getProperties() : {}])
        }
      }
    }
    return out
  },
  // Positions of blocks with one of `names` within `radius` (Euclidean, block to block) of `center`.
  find_blocks: async (serv, { names, center, radius }) => {
    if (!Array.isArray(names) || !names.length) throw new ControlError('names must be a non-empty list of block names')
    const wanted = new Set(names.map(n => blockByName(serv.registry, n).id))
    if (!(radius >= 0 && radius <= 32)) throw new ControlError(`radius must be within 0..32, got ${JSON.stringify(radius)}`)
    const c = toBlockPos(center, 'center')
    const r = Math.floor(radius)
    const out = []
    for (let x = c.x - r; x <= c.x + r; x++) {
      for (let y = Math.max(0, c.y - r); y <= Math.min(255, c.y + r); y++) {
        for (let z = c.z - r; z <= c.z + r; z++) {
          const d2 = (x - c.x) ** 2 + (y - c.y) ** 2 + (z - c.z) ** 2
          if (d2 > radius * radius) continue
          const p = c.clone().set(x, y, z)
          if (wanted.has(await serv.overworld.getBlockType(p))) out.push([x, y, z, serv.registry.blocks[await serv.overworld.getBlockType(p)].name])
        }
      }
    }
    return out
  },
  players: async (serv) => serv.players.map(p => ({
    name: p.username, pos: [p.position.x, p.position.y, p.position.z], health: p.health, gamemode: p.gameMode
  })),
  inventory: async (serv, { player }) => serv.pb.listInventory(playerNamed(serv, player)),
  give: async (serv, { player, item, count = 1 }) => serv.pb.give(playerNamed(serv, player), item, count),
  take: async (serv, { player, item, count }) => serv.pb.take(playerNamed(serv, player), item, count),
  clear: async (serv, { player }) => { serv.pb.clearInventory(playerNamed(serv, player)); return true },
  set_inventory: async (serv, { player, items = {} }) => {
    const p = playerNamed(serv, player)
    for (const name of Object.keys(items)) itemByName(serv.registry, name)
    serv.pb.closeContainer(p)
    serv.pb.clearInventory(p)
    for (const [name, count] of Object.entries(items)) serv.pb.give(p, name, count)
    return serv.pb.listInventory(p)
  },
  teleport: async (serv, { player, pos, yaw, pitch }) => {
    await serv.pb.teleport(playerNamed(serv, player), toPos(pos), yaw, pitch)
    return true
  },
  gamemode: async (serv, { player, mode }) => {
    if (!(mode in GAME_MODES)) throw new ControlError(`unknown game mode ${JSON.stringify(mode)} (valid: ${Object.keys(GAME_MODES).join(', ')})`)
    playerNamed(serv, player).setGameMode(GAME_MODES[mode])
    return true
  },
  chat: async (serv, { message }) => {
    serv.broadcast(String(message))
    serv.emit('control_event', { event: 'chat', player: null, message: String(message) })
    return true
  },
  tell: async (serv, { player, message }) => { playerNamed(serv, player).chat(String(message)); return true },
  tick_rate: async (serv, { tps }) => {
    if (!(tps >= 1 && tps <= 200)) throw new ControlError(`tps must be between 1 and 200, got ${JSON.stringify(tps)}`)
    serv.setTickInterval(tps); serv.pb.tps = tps
    return true
  },
  // random_tick_speed: vanilla's gamerule randomTickSpeed (crops grow by vanilla's rules, plugins/crops.js);
  // chance > 0 instead grows every crop one step per second with that chance (tests)
  crop_growth: async (serv, { chance = 0, random_tick_speed: speed }) => {
    if (!(chance >= 0 && chance <= 1)) throw new ControlError(`chance must be within 0..1, got ${JSON.stringify(chance)}`)
    if (speed !== undefined && !(Number.isInteger(speed) && speed >= 0 && speed <= 4096)) throw new ControlError(`random_tick_speed must be an integer 0..4096, got ${JSON.stringify(speed)}`)
    serv.pb.cropGrowthChance = chance
    if (speed !== undefined) serv.pb.randomTickSpeed = speed
    return true
  },
  // vanilla's growth speed f of the crop at `pos` (CropBlock.getGrowthSpeed; a growth step is 1 in floor(25 / f) + 1)
  crop_growth_speed: async (serv, { pos }) => serv.pb.crops.growthSpeed(toBlockPos(pos)),
  summon: async (serv, { mob, pos }) => serv.pb.mobs.summon(mob, toPos(pos)),
  mobs: async (serv) => serv.pb.mobs.list(),
  items: async (serv) => Object.values(serv.entities).filter(e => e.type === 'object' && e.itemId && !e.collected)
    .map(e => ({ id: e.id, item: serv.registry.items[e.itemId]?.name, count: e.itemCount, pos: [e.position.x, e.position.y, e.position.z], thrower: e.thrower || null })),
  // An item lying at `pos` (no velocity), picked up after `delay_ticks` (default: a block drop's).
  spawn_item: async (serv, { item, count = 1, pos, delay_ticks: delay = PICKUP.delayTicks.block }) => {
    const it = itemByName(serv.registry, item)
    if (!Number.isInteger(count) || count < 1 || count > it.stackSize) throw new ControlError(`count must be an integer 1..${it.stackSize}, got ${JSON.stringify(count)}`)
    if (!Number.isInteger(delay) || delay < 0 || delay > 6000) throw new ControlError(`delay_ticks must be an integer 0..6000, got ${JSON.stringify(delay)}`)
    const e = serv.spawnObject(serv.registry.entitiesByName.item.id, serv.overworld, toPos(pos), {
      velocity: new Vec3(0, 0, 0), itemId: it.id, itemCount: count, pickupDelayTicks: delay, deathTime: 300000
    })
    return e.id
  },
  remove_entities: async (serv) => { serv.pb.mobs.removeAll(); return true },
  set_chest: async (serv, { pos, items }) => serv.pb.chests.set(toBlockPos(pos), items),
  get_chest: async (serv, { pos }) => serv.pb.chests.get(toBlockPos(pos)),
  set_furnace: async (serv, { pos, input, fuel, output }) => serv.pb.furnaces.set(toBlockPos(pos), { input, fuel, output }),
  get_furnace: async (serv, { pos }) => serv.pb.furnaces.get(toBlockPos(pos)),
  egg_farm: async (serv, { chest, interval_s: intervalS, radius }) => { serv.pb.mobs.addEggFarm([...toBlockPos(chest).toArray()], intervalS, radius); return true },
  // Forget containers, farms and crops of the last match (the arena builder then sets them anew).
  reset_state: async (serv) => {
    for (const p of serv.players) serv.pb.closeContainer(p)
    serv.pb.chests.reset(); serv.pb.furnaces.reset(); serv.pb.crops.reset(); serv.pb.mobs.clearEggFarms(); serv.pb.mobs.removeAll()
    return true
  },
  // A replay frame (plugins/replay.js): players, items, mobs and the blocks changed since the last frame.
  replay_frame: async (serv, { start = false, stop = false }) => serv.pb.replay.frame({ start: start === true, stop: stop === true }),
  // The live view's scoreboard and centre (plugins/watch.js): {center, title, episode, t, length, scores, sides}.
  watch: async (serv, args) => serv.pb.watch.update(args),
  // The game clock (plugins/lockstep.js): its mode and tick; `speed` paces it at that multiple of real
  // time, `unpaced` lets it run as fast as the bots allow; `drop_holds` ends every hold, and every hold
  // a wait_tick still to come would take (the whistle); `game` says whether a game is on (a bot whose
  // run ended then holds the clock until its next run: plugins/lockstep.js).
  clock: async (serv, args) => serv.pb.clock.configure(args),
  hold: async (serv, { who }) => serv.pb.clock.hold(who),
  release: async (serv, { who }) => serv.pb.clock.release(who),
  wait_tick: async (serv, { tick, hold, release }) => serv.pb.clock.waitTick(tick, hold, release),
  rest: async (serv, { players, ticks }) => serv.pb.clock.rest(players, ticks),
  retire: async (serv, { players }) => serv.pb.clock.retire(players),
  free: async (serv, { players }) => serv.pb.clock.free(players),
  seed: async (serv, { seed }) => { serv.pb.seedRandom(seed); return true },
  // The order in which the server visits its players (packets, block updates, anything that loops
  // over serv.players): the online players named in `names` first, in that order, then the rest as
  // they were. Returns the new order.
  player_order: async (serv, { names }) => {
    if (!Array.isArray(names) || new Set(names).size !== names.length) throw new ControlError(`names must be a list of distinct player names, got ${JSON.stringify(names)}`)
    names.forEach(n => playerNamed(serv, n))
    const rank = (p) => { const i = names.indexOf(p.username); return i < 0 ? names.length : i }
    const order = serv.players.map((p, i) => [rank(p), i, p]).sort((a, b) => a[0] - b[0] || a[1] - b[1]).map(x => x[2])
    serv.players.splice(0, serv.players.length, ...order)
    return order.map(p => p.username)
  }
}

// What differs between the handlers and the declaration (nothing, or the server does not start).
function undeclared (ops, declared) {
  return [
    ...Object.keys(declared).filter(op => !Object.hasOwn(ops, op)).map(op => `op ${op} is declared but has no handler`),
    ...Object.keys(ops).filter(op => !Object.hasOwn(declared, op)).map(op => `op ${op} has a handler but is not declared`)
  ]
}
const PROBLEMS = undeclared(OPS, DECLARED)
if (PROBLEMS.length) throw new Error(`control.js and control_ops.json disagree: ${PROBLEMS.join('; ')}`)

// The handler of a declared op (an unknown op is refused naming the declared ones).
function handlerOf (op) {
  if (!Object.hasOwn(DECLARED, op)) throw new ControlError(`unknown op ${JSON.stringify(op)} (valid: ${Object.keys(DECLARED).join(', ')})`)
  return OPS[op]
}

// The declared types checked here, before the handler; the others (positions, lists, maps) the handlers check.
const SCALARS = {
  string: (v) => typeof v === 'string',
  integer: (v) => Number.isInteger(v),
  number: (v) => typeof v === 'number' && Number.isFinite(v),
  boolean: (v) => typeof v === 'boolean'
}

// A request's arguments against its op's declaration: each one declared, none required missing ('?':
// optional), each scalar of its declared type.
function checkArgs (op, args) {
  const declared = DECLARED[op].args
  const names = Object.keys(declared)
  for (const [name, value] of Object.entries(args)) {
    if (!Object.hasOwn(declared, name)) throw new ControlError(`op ${op} has no argument ${JSON.stringify(name)} (valid: ${names.join(', ') || 'none'})`)
    const type = declared[name].replace(/\?$/, '')
    if (Object.hasOwn(SCALARS, type) && !SCALARS[type](value)) throw new ControlError(`op ${op}: argument ${name} must be a${type === 'integer' ? 'n' : ''} ${type}, got ${JSON.stringify(value)}`)
  }
  for (const name of names) {
    if (!declared[name].endsWith('?') && args[name] === undefined) throw new ControlError(`op ${op} needs the argument ${JSON.stringify(name)}`)
  }
}

// On the lockstep clock each event says at which tick of the game it happened (docs/clock.md): events
// of one tick are one moment, which the record puts in a fixed order (pillagerbench/match/parts.py).
// One that came after the whistle (while the players were being stopped, on the wall clock) says so.
function stamped (serv, ev) {
  const tick = ev.event === 'clock' ? null : serv.pb.clock?.gameTick()
  if (tick === null || tick === undefined) return ev
  return serv.pb.clock.whistled() ? { ...ev, tick, after_whistle: true } : { ...ev, tick }
}

function attach (serv, { input, write }) {
  const reply = (obj) => write(JSON.stringify(obj) + '\n')
  serv.on('control_event', (ev) => reply(stamped(serv, ev)))
  let buffer = ''
  input.setEncoding('utf8')
  input.on('data', (chunk) => {
    buffer += chunk
    let nl
    while ((nl = buffer.indexOf('\n')) >= 0) {
      const line = buffer.slice(0, nl).trim()
      buffer = buffer.slice(nl + 1)
      if (line) clock.atBoundary(() => handle(line)) // between two ticks (js/clock/game_clock.js)
    }
  })
  async function handle (line) {
    let msg
    try { msg = JSON.parse(line) } catch (err) { return reply({ id: null, ok: false, error: `malformed control message (not JSON): ${err.message}` }) }
    const id = msg && typeof msg === 'object' ? msg.id ?? null : null
    try {
      if (!msg || typeof msg !== 'object' || typeof msg.op !== 'string') throw new ControlError('control message must be an object with a string "op"')
      const fn = handlerOf(msg.op)
      const args = msg.args ?? {}
      if (typeof args !== 'object' || Array.isArray(args)) throw new ControlError('"args" must be an object')
      checkArgs(msg.op, args)
      reply({ id, ok: true, result: (await fn(serv, args)) ?? null })
    } catch (err) {
      if (!(err instanceof ControlError)) serv.emit('pluginError', err, `control op ${msg && msg.op}`)
      reply({ id, ok: false, error: err instanceof ControlError ? err.message : `internal error: ${err.message}` })
    }
  }
  // the parent gone: an end, or an error (EPIPE, ECONNRESET: it died before reading what we wrote, e.g.
  // killed while we started); either way no one is left to play for, so the server stops, never an orphan
  input.on('end', () => serv.emit('control_closed'))
  input.on('error', () => serv.emit('control_closed'))
}

module.exports = { attach, OPS, undeclared }
