'use strict'
// Waiting a number of game ticks that always ends.
// mineflayer's bot.waitForTicks counts 'physicsTick' events, which mineflayer does not emit while
// the chunk under the bot is not loaded (right after a teleport, or while the server is slow to
// send it); it then rejects after 5 s. Here a wait ends after `n` physics ticks or after the
// wall-clock time of `n` ticks plus a little slack, whichever comes first.
const { TICK_MS } = require('../clock/game_clock')
const SLACK_MS = 250

function waitTicks (bot, n) {
  const ticks = Math.floor(Number(n))
  if (!(ticks > 0)) return Promise.resolve()
  return new Promise(resolve => {
    let left = ticks
    const done = () => {
      clearTimeout(timer)
      bot.removeListener('physicsTick', onTick)
      resolve()
    }
    const onTick = () => { if (--left <= 0) done() }
    const timer = setTimeout(done, ticks * TICK_MS + SLACK_MS)
    bot.on('physicsTick', onTick)
  })
}

module.exports = { waitTicks }
