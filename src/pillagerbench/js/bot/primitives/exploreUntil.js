'use strict'
// exploreUntil(bot, direction, maxTime = 60, callback): walk in `direction` (a Vec3 of -1/0/1
// components) with some randomness until callback() returns something truthy or maxTime seconds pass.
const { helpers } = require('./util')

module.exports = {
  name: 'exploreUntil',
  make (ctx) {
    // eslint-disable-next-line no-unused-vars -- kept as written (primitives change only with their fidelity tests)
    const { bot, run, goals } = ctx
    const h = helpers(ctx)

    async function exploreUntil (_bot, direction, maxTime = 60, callback = () => false) {
      const dir = h.toVec3(direction, 'direction for exploreUntil')
      if (![dir.x, dir.y, dir.z].every(v => v === -1 || v === 0 || v === 1) || (dir.x === 0 && dir.y === 0 && dir.z === 0)) {
        throw new Error('direction for exploreUntil must be a Vec3 with components -1, 0 or 1, not all 0')
      }
      if (typeof callback !== 'function') throw new Error('callback for exploreUntil must be a function')
      const deadline = Date.now() + maxTime * 1000
      while (true) {
        const found = await callback()
        if (found) { ctx.chat('Explore success.'); return found }
        if (Date.now() >= deadline) { ctx.chat('Max exploration time reached'); return null }
        const r = () => Math.floor(Math.random() * 20) + 10
        const p = bot.entity.position
        const goal = new goals.GoalNearXZ(p.x + dir.x * r(), p.z + dir.z * r(), 2)
        bot.pathfinder.setGoal(goal)
        await h.waitTicks(40)
      }
    }

    return { exploreUntil }
  }
}
