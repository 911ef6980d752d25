'use strict'
// The pathfinder's Movements for our bots, with a cheaper block lookup.
// mineflayer-pathfinder asks `movements.getBlock` for every neighbour of every node it visits;
// the stock one builds a full prismarine Block per call (biome, light, block entity) through
// bot.blockAt and then derives the flags it needs. Profiles of a match showed about three quarters
// of the path search in it. Here the derived flags are computed once per block state and every
// call returns a small object that inherits them, with its own position and height: the same
// answers (see tests/players/test_movements_js.py), at a fraction of the work, so the search
// visits as many nodes in a smaller share of each tick (sandbox.js PATH_TICK_MS).
const { Movements } = require('mineflayer-pathfinder')
const { Vec3 } = require('vec3')
const clock = require('../clock/game_clock')

function missing (dy) {
  return { replaceable: false, canFall: false, safe: false, physical: false, liquid: false, climbable: false, height: dy, openable: false }
}

function fastGetBlock (m, bot) {
  const Block = require('prismarine-block')(bot.registry)
  const templates = new Map() // stateId -> Block with the flags getBlock derives, and `top`
  const probe = new Vec3(0, 0, 0)
  const inChunk = new Vec3(0, 0, 0)

  function template (stateId) {
    const b = Block.fromStateId(stateId, 0)
    b.climbable = m.climbables.has(b.type)
    b.safe = (b.boundingBox === 'empty' || b.climbable || m.carpets.has(b.type)) && !m.blocksToAvoid.has(b.type)
    b.physical = b.boundingBox === 'block' && !m.fences.has(b.type)
    b.replaceable = m.replaceables.has(b.type) && !b.physical
    b.liquid = m.liquids.has(b.type)
    b.canFall = m.gravityBlocks.has(b.type)
    b.openable = m.openable.has(b.type)
    let top = 0
    for (const shape of b.shapes) top = Math.max(top, shape[4])
    b.top = top
    return b
  }

  return function getBlock (pos, dx, dy, dz) {
    if (!pos) return missing(dy)
    const x = Math.floor(pos.x + dx)
    const y = Math.floor(pos.y + dy)
    const z = Math.floor(pos.z + dz)
    probe.set(x, y, z)
    const column = m.pbColumns ? m.pbColumns(x, z, probe) : bot.world.getColumnAt(probe)
    if (!column) return missing(dy)
    const stateId = column.getBlockStateId(inChunk.set(x & 15, y, z & 15))
    let t = templates.get(stateId)
    if (t === undefined) {
      t = template(stateId)
      templates.set(stateId, t)
    }
    const b = Object.create(t)
    b.position = new Vec3(x, y, z)
    b.height = t.top > 0 ? pos.y + dy + t.top : pos.y + dy
    return b
  }
}

// The world's loaded columns by a number instead of prismarine-world's "x,z" string: found once, kept
// until a column is loaded or unloaded (its events) or the bot's world is replaced (a respawn). One per
// bot, shared by all its Movements (agent code may make a new one on every call).
const columnCaches = new WeakMap() // bot -> its columnAt
const FAR = 1 << 24 // blocks within ±2^24 on x and z take the fast way (chunks within ±2^20)
const CHUNK_SPAN = 1 << 21
function loadedColumns (bot) {
  if (!columnCaches.has(bot)) columnCaches.set(bot, columnCache(bot))
  return columnCaches.get(bot)
}
function columnCache (bot) {
  const columns = new Map()
  let world = null
  let last = { cx: NaN, cz: NaN, column: undefined } // most lookups are in the column of the one before
  const forget = () => { columns.clear(); last = { cx: NaN, cz: NaN, column: undefined } }
  return function columnAt (x, z, probe) {
    if (bot.world !== world) {
      if (world) { world.off('chunkColumnLoad', forget); world.off('chunkColumnUnload', forget) }
      world = bot.world
      forget()
      world.on('chunkColumnLoad', forget)
      world.on('chunkColumnUnload', forget)
    }
    if (!(Math.abs(x) < FAR && Math.abs(z) < FAR)) return world.getColumnAt(probe)
    const cx = x >> 4
    const cz = z >> 4
    if (cx === last.cx && cz === last.cz) return last.column
    const key = (cx + CHUNK_SPAN / 2) * CHUNK_SPAN + cz + CHUNK_SPAN / 2
    let column = columns.get(key)
    if (column === undefined) {
      column = world.getColumnAt(probe)
      if (!column) return column
      columns.set(key, column)
    }
    last = { cx, cz, column }
    return column
  }
}

// The blocks other entities stand in, by a number instead of the stock "x,y,z" string (each lookup
// built and interned a string: a sixth of a search). Rebuilt whenever the stock index is: its
// `updateCollisionIndex` and `clearCollisionIndex`. Whole-block positions within ±2^19 on x and z and
// ±2^11 on y take the fast way; any other position the stock one.
// With the column cache above, a node costs two thirds of what it did (benchmarks/path_search.py).
// Only on the lockstep clock, where a search visits a fixed number of nodes per tick: there a cheaper
// node is the same game sooner. On the real clock it would be more nodes per 7 ms slice, another
// search, and that clock's reference figures were measured with the stock lookups.
const XZ = 1 << 20
const Y = 1 << 12
const blockKey = (x, y, z) => ((x + XZ / 2) * XZ + (z + XZ / 2)) * Y + (y + Y / 2)
const fits = (x, y, z) => Number.isInteger(x) && Number.isInteger(y) && Number.isInteger(z) &&
  Math.abs(x) < XZ / 2 && Math.abs(z) < XZ / 2 && Math.abs(y) < Y / 2

function fastSearch (m, bot) {
  m.pbColumns = loadedColumns(bot) // what getBlock asks for its column (fastGetBlock)
  let index = new Map()
  const rebuild = () => {
    index = new Map()
    for (const [key, n] of Object.entries(m.entityIntersections)) {
      const [x, y, z] = key.split(',').map(Number)
      if (!fits(x, y, z)) { index = null; return } // a key the fast way cannot hold: the stock lookup
      index.set(blockKey(x, y, z), n)
    }
  }
  for (const name of ['updateCollisionIndex', 'clearCollisionIndex']) {
    const stock = m[name]
    m[name] = function (...args) { const out = stock.apply(this, args); rebuild(); return out }
  }
  const stockCount = m.getNumEntitiesAt
  m.getNumEntitiesAt = function (pos, dx, dy, dz) {
    if (this.allowEntityDetection === false || !pos) return 0
    const x = pos.x + dx
    const y = pos.y + dy
    const z = pos.z + dz
    if (index === null || !fits(x, y, z)) return stockCount.call(this, pos, dx, dy, dz)
    return index.get(blockKey(x, y, z)) ?? 0
  }
  rebuild()
}

// Our defaults: no digging, no towers, no parkour (agent code may change the options it is given).
function defaultMovements (bot) {
  const m = new Movements(bot)
  m.canDig = false
  m.allow1by1towers = false
  m.scafoldingBlocks = []
  m.allowParkour = false
  m.getBlock = fastGetBlock(m, bot)
  if (clock.lockstep) fastSearch(m, bot)
  return m
}

module.exports = { defaultMovements, fastGetBlock, fastSearch }
