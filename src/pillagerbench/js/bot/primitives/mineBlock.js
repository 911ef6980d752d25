'use strict'
// mineBlock(bot, name, count = 1, point = null, maxDistance = 32), blockExists(bot, name, point, maxDistance = 32)
const { helpers, checkString, checkNumber } = require('./util')
const { collector } = require('./collect')

module.exports = {
  name: 'mineBlock',
  make (ctx) {
    const { bot, run, mcData } = ctx
    const h = helpers(ctx)
    const { collect } = collector(ctx, h)

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
      await collect(targets, {
        act: async (target) => {
          const tool = bot.pathfinder.bestHarvestTool(target)
          if (tool) await run.race(bot.equip(tool, 'hand'))
          if (!target.canHarvest?.(bot.heldItem ? bot.heldItem.type : null) && target.harvestTools) {
            ctx.chat(`I need at least a ${Object.keys(target.harvestTools).map(id => mcData.items[id].name)[0]} to mine ${name}!  Skip it!`)
            return false
          }
          await run.race(bot.dig(target)) // mineflayer's default: turn to the block at its head speed first, as collectblock
        }
      })
      ctx.chat(`Mined ${targets.length} ${name}`) // the blocks found, as upstream's chat
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
