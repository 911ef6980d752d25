'use strict'
// placeItem(bot, name, position): place a block from the inventory at `position`.
const { helpers, checkString } = require('./util')

const FACES = [[0, 1, 0], [0, -1, 0], [1, 0, 0], [-1, 0, 0], [0, 0, 1], [0, 0, -1]]
const EMPTY = new Set(['air', 'cave_air', 'void_air', 'water', 'lava', 'grass', 'tall_grass'])

// Does an entity's box overlap the block cell at `pos`? A player's box is grown by 0.3 on each
// side: it may be walking into the cell while the block is on its way.
function overlaps (e, pos) {
  const w = (e.width || 0.6) / 2 + (e.type === 'player' ? 0.3 : 0)
  const h = e.height || 1.8
  return e.position.x + w > pos.x && e.position.x - w < pos.x + 1 && e.position.z + w > pos.z && e.position.z - w < pos.z + 1 &&
    e.position.y + h > pos.y && e.position.y < pos.y + 1
}

module.exports = {
  name: 'placeItem',
  make (ctx) {
    const { bot, run, mcData, goals, Vec3 } = ctx
    const h = helpers(ctx)
    const TOO_MANY = 'placeItem failed too many times, please find another position to place'

    async function placeItem (_bot, name, position) {
      checkString(name, 'name for placeItem')
      const pos = h.toVec3(position, 'position for placeItem').floored()
      if (!mcData.itemsByName[name]) throw new Error(`No item named ${name}`)
      const item = h.findItem(name)
      if (!item) {
        ctx.chat(`No ${name} in inventory`)
        return
      }
      const before = h.itemCount(name)
      let reference = null
      let face = null
      for (const [dx, dy, dz] of FACES) {
        const b = bot.blockAt(pos.offset(dx, dy, dz))
        if (b && !EMPTY.has(b.name)) { reference = b; face = new Vec3(-dx, -dy, -dz); break }
      }
      if (!reference) {
        ctx.chat(`No block to place ${name} on. You cannot place a floating block.`)
        run.fail('placeItem', TOO_MANY)
        return
      }
      try {
        if (bot.entity.position.distanceTo(pos.offset(0.5, 0.5, 0.5)) > 4.2 ||
            bot.entity.position.floored().equals(pos) || bot.entity.position.floored().offset(0, 1, 0).equals(pos)) {
          await h.goto(new goals.GoalPlaceBlock(pos, bot.world, { range: 4 }), { quiet: false })
        }
        // The server refuses (as vanilla does) a block into a taken space or into someone's box: ask first.
        const there = bot.blockAt(pos)
        if (there && !EMPTY.has(there.name)) throw new Error(`${there.name} is already at ${pos}`)
        const inTheWay = Object.values(bot.entities).find(e => (e.type === 'player' || e.type === 'mob') && overlaps(e, pos))
        if (inTheWay) throw new Error(`${inTheWay.username || inTheWay.name} is in the way at ${pos}`)
        await run.race(bot.equip(h.findItem(name), 'hand'))
        await run.race(bot.placeBlock(reference, face))
        ctx.chat(`Placed ${name}`)
        ctx.save(`${name}_placed`)
      } catch (err) {
        if (h.isStop(err) || !run.active) throw err
        if (h.itemCount(name) < before) {
          ctx.chat(`Placed ${name}`)
          ctx.save(`${name}_placed`)
          return
        }
        ctx.chat(`Error placing ${name}: ${err.message}, please find another position to place`)
        run.fail('placeItem', TOO_MANY)
      }
    }

    return { placeItem }
  }
}
