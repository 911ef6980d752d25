'use strict'
// craftItem(bot, name, count = 1): `count` is the number of times the recipe is done.
const { helpers, checkString, checkNumber } = require('./util')

module.exports = {
  name: 'craftItem',
  make (ctx) {
    const { bot, run, mcData } = ctx
    const h = helpers(ctx)
    const TOO_MANY = 'craftItem failed too many times, check chat log to see what happened'

    // What is missing for the recipe that needs the fewest extra items.
    function missingFor (recipes) {
      let best = null
      for (const r of recipes) {
        const need = {}
        const ingredients = r.delta.filter(d => d.count < 0)
        for (const d of ingredients) need[d.id] = (need[d.id] || 0) - d.count
        const missing = []
        let total = 0
        for (const [id, n] of Object.entries(need)) {
          const have = bot.inventory.count(Number(id), null)
          if (have < n) { missing.push([mcData.items[id].name, n - have]); total += n - have }
        }
        if (!best || total < best.total) best = { total, missing }
      }
      return best
    }

    async function craftItem (_bot, name, count = 1) {
      checkString(name, 'name for craftItem')
      checkNumber(count, 'count for craftItem')
      const item = mcData.itemsByName[name]
      if (!item) throw new Error(`No item named ${name}`)
      const tablePos = bot.findBlock({ matching: mcData.blocksByName.crafting_table.id, maxDistance: 32 })
      if (!tablePos) {
        ctx.chat('Craft without a crafting table')
      } else if (bot.entity.position.distanceTo(tablePos.position.offset(0.5, 0.5, 0.5)) > 4) {
        await h.goto(h.near(tablePos.position, 2))
      }
      const table = tablePos ? bot.blockAt(tablePos.position) : null
      const recipe = bot.recipesFor(item.id, null, 1, table)[0]
      if (recipe) {
        ctx.chat(`I can make ${name}`)
        try {
          await run.race(bot.craft(recipe, count, table))
          ctx.chat(`I did the recipe for ${name} ${count} times`)
        } catch (err) {
          if (h.isStop(err) || !run.active) throw err
          ctx.chat(`I cannot do the recipe for ${name} ${count} times`)
        }
        return
      }
      // as upstream's: without a table only the 2x2 recipes count, and none means 'No crafting table nearby'
      const all = bot.recipesAll(item.id, null, table)
      if (all.length === 0) {
        if (!table && bot.recipesAll(item.id, null, true).length > 0) throw new Error('No crafting table nearby')
        throw new Error(`There is no recipe for ${name}`)
      }
      const { missing } = missingFor(all)
      ctx.chat(`I cannot make ${name} because I need: ${missing.map(([n, k]) => `${k} more ${n}`).join(', ')}`)
      run.fail('craftItem', TOO_MANY)
    }

    return { craftItem }
  }
}
