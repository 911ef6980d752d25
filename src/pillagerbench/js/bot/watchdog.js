'use strict'
// The pathfinder watchdog of upstream's /step (reference §1.4; its index.js ran it on every step):
// mineflayer-pathfinder sometimes stops moving with its goal still set, and nothing then settles a
// goto() that waits for it: the bot stands still for the rest of the episode. Every 20 ticks of a run
// the watchdog looks; after 5 looks in a row that find a goal that is not reached, no path being
// walked and a last search that found one (a goal with no path is left alone: goto() has given up
// on it), it sets the same goal again (same `dynamic` flag), so the pathfinder searches afresh.
// Upstream's second watchdog, a /tp for a bot that walks without getting anywhere, is not ours:
// agents have no commands here (docs/fair-play.md).
const LOOK_TICKS = 20
const LOOKS = 5

function remember (bot) {
  // which flag the current goal was set with (the pathfinder keeps it to itself)
  const setGoal = bot.pathfinder.setGoal
  bot.pathfinder.pbDynamic = false
  bot.pathfinder.setGoal = (goal, dynamic = false) => {
    bot.pathfinder.pbDynamic = Boolean(dynamic)
    return setGoal(goal, dynamic)
  }
  bot.pathfinder.pbLastStatus = null
  bot.on('path_update', (r) => { bot.pathfinder.pbLastStatus = r.status })
}

// A physicsTick listener for one run; onReset(goal) is told each time it sets a goal again.
function watchdog (bot, onReset = () => {}) {
  let ticks = 0
  let looks = 0
  return () => {
    if (++ticks < LOOK_TICKS) return
    ticks = 0
    const pf = bot.pathfinder
    const goal = pf.goal
    const stuck = goal && !pf.isMoving() && pf.pbLastStatus !== 'noPath' &&
      !goal.isEnd(bot.entity.position.floored())
    looks = stuck ? looks + 1 : 0
    if (looks < LOOKS) return
    looks = 0
    pf.setGoal(goal, pf.pbDynamic)
    onReset(goal)
  }
}

module.exports = { remember, watchdog, LOOK_TICKS, LOOKS }
