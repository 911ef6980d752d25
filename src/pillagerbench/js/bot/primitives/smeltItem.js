'use strict'
// smeltItem(bot, itemName, fuelName, count = 1)
const { helpers, checkString, checkNumber } = require('./util')

// per item, as upstream's: a fixed 12 s wait (the furnace needs 10 s), then the output is taken
const WAIT_TICKS = 240

module.exports = {
  name: 'smeltItem',
  make (ctx) {
    const { bot, run, mcData } = ctx
    const h = helpers(ctx)
    const TOO_MANY = 'smeltItem failed too many times, please check the fuel and input'

    async function openFree (positions) {
      for (const pos of positions) {
        if (bot.entity.position.distanceTo(pos.offset(0.5, 0.5, 0.5)) > 4) await h.goto(h.near(pos, 2))
        const furnace = await run.race(bot.openFurnace(bot.blockAt(pos)))
        if (!furnace.inputItem() && !furnace.outputItem()) return furnace
        furnace.close()
      }
      return null
    }

    async function smeltItem (_bot, itemName, fuelName, count = 1) {
      checkString(itemName, 'itemName for smeltItem')
      checkString(fuelName, 'fuelName for smeltItem')
      checkNumber(count, 'count for smeltItem')
      const item = mcData.itemsByName[itemName]
      const fuel = mcData.itemsByName[fuelName]
      if (!item) throw new Error(`No item named ${itemName}`)
      if (!fuel) throw new Error(`No item named ${fuelName}`)
      const have = h.itemCount(itemName)
      if (have === 0) {
        ctx.chat(`No ${itemName} in inventory`)
        return
      }
      count = Math.min(Math.floor(count), have)
      const furnaces = bot.findBlocks({ matching: mcData.blocksByName.furnace.id, maxDistance: 32, count: 16 })
      if (furnaces.length === 0) {
        ctx.chat('No furnace nearby')
        return
      }
      const furnace = await openFree(furnaces)
      if (!furnace) {
        ctx.chat('No available furnace')
        return
      }
      run.cleanups.push(() => { try { furnace.close() } catch (_) {} })
      ctx.chat(`Smelting ${count} ${itemName} with ${fuelName}`)
      let done = 0
      try {
        for (let i = 0; i < count; i++) {
          if ((furnace.fuelSeconds ?? 0) < 15 && furnace.fuelItem()?.name !== fuelName) {
            if (h.itemCount(fuelName) === 0) { ctx.chat(`No ${fuelName} as fuel in inventory`); break }
            await run.race(furnace.putFuel(fuel.id, null, 1))
          }
          await run.race(furnace.putInput(item.id, null, 1))
          await h.waitTicks(WAIT_TICKS)
          if (!furnace.outputItem()) throw new Error(`${itemName} is not a valid input`)
          await run.race(furnace.takeOutput())
          done++
        }
      } catch (err) {
        if (h.isStop(err) || !run.active) throw err
        if (/not a valid input/.test(err.message)) { furnace.close(); throw err }
      }
      furnace.close()
      if (done > 0) {
        ctx.chat(`Smelted ${done} ${itemName}.`)
      } else {
        ctx.chat(`Failed to smelt ${itemName}, please check the fuel and input.`)
        run.fail('smeltItem', TOO_MANY)
      }
    }

    return { smeltItem }
  }
}
