'use strict'
// mineBlock(bot, name, count = 1, point = null, maxDistance = 32), blockExists(bot, name, point, maxDistance = 32)
const { helpers, checkString, checkNumber } = require('./util')

module.exports = {
  name: 'mineBlock',
  make (ctx) {
    const { bot, run, mcData } = ctx
    const h = helpers(ctx)

    function blockType (name) {
      const block = mcData.blocksByName[name]
      if (!block) throw new Error(`No block named ${name}`)
      return block
    }

    async function mineBlock (_bot, name, count = 1, point = null, maxDistance = 32) {
      checkString(name, 'name for mineBlock')
      checkNumber(count, 'count for mineBlock')
      const block = blockType(name)
      const center = point ? h.toVec3(point, 'point for mineBlock') : bot.entity.position
      const targets = bot.findBlocks({ matching: block.id, maxDistance, count: Math.max(1, Math.floor(count)), point: center })
      if (targets.length === 0) {
        ctx.chat(`No ${name} nearby, please explore first`)
        run.fail('mineBlock', 'mineBlock failed too many times, make sure you explore before calling mineBlock')
        return
      }
      let mined = 0
      for (const pos of h.nearestFirst(targets)) { // nearest to the bot each time, as upstream's collectblock
        const target = bot.blockAt(pos)
        if (!target || target.type !== block.id) continue
        if (bot.entity.position.distanceTo(pos.offset(0.5, 0.5, 0.5)) > 4) {
          await h.goto(h.near(pos, 2))
        }
        const now = bot.blockAt(pos)
        if (!now || now.type !== block.id) continue
        // unreachable (the server refuses digs more than 6 blocks from the eyes, vanilla's reach): skip it
        if (bot.entity.position.offset(0, 1.5, 0).distanceTo(pos.offset(0.5, 0.5, 0.5)) > 5.9) continue
        const tool = bot.pathfinder.bestHarvestTool(now)
        if (tool) await run.race(bot.equip(tool, 'hand'))
        if (!now.canHarvest?.(bot.heldItem ? bot.heldItem.type : null) && now.harvestTools) {
          ctx.chat(`I need at least a ${Object.keys(now.harvestTools).map(id => mcData.items[id].name)[0]} to mine ${name}!  Skip it!`)
          continue
        }
        try {
          await run.race(bot.dig(now, true))
        } catch (err) {
          if (h.isStop(err) || !run.active) throw err
          continue
        }
        mined++
        await h.collectDrops(pos.offset(0.5, 0.5, 0.5))
      }
      ctx.chat(`Mined ${mined} ${name}`)
      ctx.save(`${name}_mined`)
    }

    function blockExists (_bot, name, point = null, maxDistance = 32) {
      const block = blockType(name)
      const center = point ? h.toVec3(point, 'point for blockExists') : bot.entity.position
      return bot.findBlocks({ matching: block.id, maxDistance, count: 1, point: center }).length > 0
    }

    return { mineBlock, blockExists }
  }
}
