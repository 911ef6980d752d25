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
    const column = bot.world.getColumnAt(probe.set(x, y, z))
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

// Our defaults: no digging, no towers, no parkour (agent code may change the options it is given).
function defaultMovements (bot) {
  const m = new Movements(bot)
  m.canDig = false
  m.allow1by1towers = false
  m.scafoldingBlocks = []
  m.allowParkour = false
  m.getBlock = fastGetBlock(m, bot)
  return m
}

module.exports = { defaultMovements, fastGetBlock }
