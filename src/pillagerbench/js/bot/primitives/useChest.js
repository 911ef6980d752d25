'use strict'
// getItemFromChest(bot, chestPosition, itemsToGet), depositItemIntoChest(bot, chestPosition, itemsToDeposit),
// checkItemInsideChest(bot, chestPosition)
const { helpers } = require('./util')

module.exports = {
  name: 'useChest',
  make (ctx) {
    const { bot, run, mcData } = ctx
    const h = helpers(ctx)

    function contentsOf (chest) {
      const out = {}
      for (const it of chest.containerItems()) out[it.name] = (out[it.name] || 0) + it.count
      return out
    }

    async function openChestAt (chestPosition) {
      const pos = h.toVec3(chestPosition, 'chestPosition').floored()
      const block = bot.blockAt(pos)
      if (!block || block.name !== 'chest') {
        ctx.observer.setChest(pos, 'Invalid')
        throw new Error(`No chest at ${pos}, it is ${block ? block.name : 'not loaded'}`)
      }
      if (bot.entity.position.distanceTo(pos.offset(0.5, 0.5, 0.5)) > 4) await h.goto(h.near(pos, 2))
      const chest = await run.race(bot.openContainer(bot.blockAt(pos)))
      run.cleanups.push(() => { try { chest.close() } catch (_) {} })
      return { chest, pos }
    }

    function closeChest (chest, pos) {
      ctx.observer.setChest(pos, contentsOf(chest))
      chest.close()
    }

    async function getItemFromChest (_bot, chestPosition, itemsToGet) {
      const { chest, pos } = await openChestAt(chestPosition)
      try {
        for (const [name, want] of Object.entries(itemsToGet || {})) {
          const item = mcData.itemsByName[name]
          if (!item) { ctx.chat(`No item named ${name}`); continue }
          const there = chest.containerItems().filter(i => i.type === item.id).reduce((a, i) => a + i.count, 0)
          if (there === 0) { ctx.chat(`I don't see ${name} in this chest`); continue }
          if (there < want) ctx.chat(`Not enough ${name} in chest.`)
          await run.race(chest.withdraw(item.id, null, Math.min(there, want)))
        }
      } finally {
        if (run.active) closeChest(chest, pos)
      }
    }

    async function depositItemIntoChest (_bot, chestPosition, itemsToDeposit) {
      const { chest, pos } = await openChestAt(chestPosition)
      try {
        for (const [name, want] of Object.entries(itemsToDeposit || {})) {
          const item = mcData.itemsByName[name]
          if (!item) { ctx.chat(`No item named ${name}`); continue }
          const have = h.itemCount(name)
          if (have === 0) { ctx.chat(`No ${name} in inventory`); continue }
          if (have < want) ctx.chat(`Not enough ${name} in inventory.`)
          await run.race(chest.deposit(item.id, null, Math.min(have, want)))
        }
      } finally {
        if (run.active) closeChest(chest, pos)
      }
    }

    async function checkItemInsideChest (_bot, chestPosition) {
      const { chest, pos } = await openChestAt(chestPosition)
      const contents = contentsOf(chest)
      closeChest(chest, pos)
      return contents
    }

    return { getItemFromChest, depositItemIntoChest, checkItemInsideChest }
  }
}
