'use strict'
// killMob(bot, mobName, timeout = 300): timeout in seconds.
const { helpers, checkString, checkNumber } = require('./util')

module.exports = {
  name: 'killMob',
  make (ctx) {
    const { bot, run, goals } = ctx
    const h = helpers(ctx)
    const TOO_MANY = 'killMob failed too many times, make sure you explore before calling killMob'

    async function killMob (_bot, mobName, timeout = 300) {
      checkString(mobName, 'mobName for killMob')
      checkNumber(timeout, 'timeout for killMob')
      const dead = ctx.observer.dead
      const target = bot.nearestEntity(e => (mobName === 'player' ? e.type === 'player' : e.name === mobName) &&
        e !== bot.entity && !dead.has(e.id) && e.position.distanceTo(bot.entity.position) < 48)
      if (!target) {
        ctx.chat(`No ${mobName} nearby, please explore first`)
        run.fail('killMob', TOO_MANY)
        return
      }
      const deadline = Date.now() + timeout * 1000
      let lastPos = target.position.clone()
      const gone = () => !bot.entities[target.id] || target.isValid === false || dead.has(target.id)
      while (!gone()) {
        if (Date.now() > deadline) throw new Error(`Failed to kill ${mobName}.`)
        lastPos = target.position.clone()
        const d = bot.entity.position.distanceTo(target.position)
        if (d > 3) {
          const reached = await h.goto(new goals.GoalFollow(target, 2))
          if (!reached && bot.entity.position.distanceTo(target.position) > 3) await h.waitTicks(10)
          continue
        }
        await run.race(bot.lookAt(target.position.offset(0, (target.height || 1) * 0.5, 0), true))
        bot.attack(target)
        await h.waitTicks(10)
      }
      // Drops appear where it died and can be picked up after half a second: stand there meanwhile.
      await h.goto(h.near(new ctx.Vec3(lastPos.x, bot.entity.position.y, lastPos.z), 1))
      await h.collectDrops(lastPos, { radius: 4, waitTicks: 12 })
      ctx.chat(`Killed ${mobName}!`)
      ctx.save(`${mobName}_killed`)
    }

    return { killMob }
  }
}
