'use strict'
// giveToPlayer(bot, itemName, playerName, count = -1), goToPlayer(bot, playerName, distance = 2), discard(bot, itemName, count = -1)
const { helpers, checkString, checkNumber } = require('./util')

module.exports = {
  name: 'giveToPlayer',
  make (ctx) {
    const { bot, run, mcData, goals } = ctx
    const h = helpers(ctx)

    function playerEntity (username) {
      const p = bot.players[username]
      if (!p || !p.entity) throw new Error(`Could not find ${username}.`)
      return p.entity
    }

    async function goToPlayer (_bot, username, distance = 2) {
      checkString(username, 'playerName for goToPlayer')
      const entity = playerEntity(username)
      if (bot.entity.position.distanceTo(entity.position) > distance + 0.5) {
        await h.goto(new goals.GoalFollow(entity, distance))
      }
      return true
    }

    async function tossCount (name, count) {
      const item = mcData.itemsByName[name]
      const have = h.itemCount(name)
      const n = count < 0 ? have : Math.min(count, have)
      if (n > 0) await run.race(bot.toss(item.id, null, n))
      return n
    }

    async function giveToPlayer (_bot, itemName, username, count = -1) {
      checkString(itemName, 'itemName for giveToPlayer')
      checkString(username, 'playerName for giveToPlayer')
      checkNumber(count, 'count for giveToPlayer')
      const entity = playerEntity(username)
      if (!mcData.itemsByName[itemName]) throw new Error(`No item named ${itemName}`)
      if (h.itemCount(itemName) === 0) {
        ctx.chat(`I do not have any ${itemName} to give.`)
        return false
      }
      await goToPlayer(_bot, username, 2)
      await run.race(bot.lookAt(entity.position.offset(0, 1.0, 0)))
      await h.waitTicks(5)
      const n = await tossCount(itemName, count)
      ctx.chat(`Gave ${n} ${itemName} to ${username}`)
      return true
    }

    async function discard (_bot, itemName, count = -1) {
      checkString(itemName, 'itemName for discard')
      if (!mcData.itemsByName[itemName]) throw new Error(`No item named ${itemName}`)
      return tossCount(itemName, count)
    }

    return { giveToPlayer, goToPlayer, discard }
  }
}
