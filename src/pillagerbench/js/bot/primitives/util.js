'use strict'
// Helpers shared by the primitives. `helpers(ctx)` binds them to one run.
const { isStop } = require('../run')
const ticks = require('../ticks')

function helpers (ctx) {
  const { bot, run, Vec3, goals } = ctx

  const toVec3 = (p, what = 'position') => {
    if (p instanceof Vec3) return p
    if (Array.isArray(p) && p.length === 3 && p.every(Number.isFinite)) return new Vec3(p[0], p[1], p[2])
    if (p && Number.isFinite(p.x) && Number.isFinite(p.y) && Number.isFinite(p.z)) return new Vec3(p.x, p.y, p.z)
    throw new Error(`${what} must be a Vec3, e.g. new Vec3(x, y, z)`)
  }

  const items = () => bot.inventory.items()
  const itemCount = (name) => items().filter(i => i.name === name).reduce((a, i) => a + i.count, 0)
  const findItem = (name) => items().find(i => i.name === name) || null
  const waitTicks = (n) => run.race(ticks.waitTicks(bot, n))

  // Walk to a goal; gives up quietly (returns false) when there is no path.
  async function goto (goal, { quiet = true } = {}) {
    run.check()
    try {
      await run.race(bot.pathfinder.goto(goal))
      return true
    } catch (err) {
      if (isStop(err) || !run.active) throw err
      if (!quiet) throw err
      return false
    }
  }

  const near = (pos, range) => new goals.GoalNear(pos.x, pos.y, pos.z, range)

  // Pick up the item entities that appear within `radius` of `center` (drops of a dug block or a mob).
  async function collectDrops (center, { radius = 3, waitTicks: wait = 3, timeoutMs = 4000 } = {}) {
    const nearby = () => Object.values(bot.entities).filter(e => e.name === 'item' && e.isValid !== false &&
      e.position.distanceTo(center) <= radius)
    let found = nearby()
    for (let i = 0; i < wait && found.length === 0; i++) { await waitTicks(1); found = nearby() }
    const deadline = Date.now() + timeoutMs
    while (found.length && Date.now() < deadline) {
      found.sort((a, b) => a.position.distanceTo(bot.entity.position) - b.position.distanceTo(bot.entity.position))
      const target = found[0]
      if (bot.entity.position.distanceTo(target.position) > 1.2) await goto(near(target.position, 0.8))
      await waitTicks(2)
      found = nearby()
    }
    return found.length === 0
  }

  async function equipItem (name, dest = 'hand') {
    const it = findItem(name)
    if (!it) return false
    await run.race(bot.equip(it, dest))
    return true
  }

  // Blocks with one of `ids` within `radius` (horizontally) and `dy` layers of `center`, nearest first.
  // Faster than findBlocks for blocks that fill whole layers (dirt under the ground).
  function scanBlocks (center, ids, { radius = 32, dy = 4 } = {}) {
    const c = center.floored()
    const want = new Set(ids)
    const out = []
    const p = new Vec3(0, 0, 0)
    for (let y = Math.max(0, c.y - dy); y <= Math.min(255, c.y + dy); y++) {
      for (let x = c.x - radius; x <= c.x + radius; x++) {
        for (let z = c.z - radius; z <= c.z + radius; z++) {
          if ((x - c.x) ** 2 + (z - c.z) ** 2 > radius * radius) continue
          const sid = bot.world.getBlockStateId(p.set(x, y, z))
          const b = sid === undefined ? null : bot.registry.blocksByStateId[sid]
          if (b && want.has(b.id)) out.push(new Vec3(x, y, z))
        }
      }
    }
    return out.sort((a, b) => a.distanceSquared(c) - b.distanceSquared(c))
  }

  return { toVec3, items, itemCount, findItem, waitTicks, goto, near, collectDrops, equipItem, isStop, scanBlocks }
}

function checkString (value, what) {
  if (typeof value !== 'string') throw new Error(`${what} must be a string`)
}
function checkNumber (value, what) {
  if (typeof value !== 'number' || !Number.isFinite(value)) throw new Error(`${what} must be a number`)
}

module.exports = { helpers, checkString, checkNumber }
