'use strict'
// Nothing acts on the world for a run that has stopped. Stopping settles the run at once (run.js),
// but mineflayer keeps going with what it had started: bot.dig and bot.activateBlock first turn the
// head at 3 rad/s and only then send their packet, so a dig begun just before the stop would break
// its block up to a second later. `gate(bot, owner)` drops the packets that change the world (dig
// start and finish, drop items, use on a block, an entity or in the air) while the run `owner()`
// gives is missing or stopped.
// Cancelling a dig and releasing a used item stay allowed: halt() sends them.
// A dig acts only for the run that began it (`owner()` when bot.dig was called): a dig still turning
// the head when its run stopped would otherwise send its start and finish once the next run (the next
// episode) is active, and break a block there before that run's code has done anything.
const BLOCK_DIG_ACTS = new Set([0, 2, 3, 4]) // start, finish, drop stack, drop item
const DIGGING = new Set([0, 2]) // start, finish: a dig's own
const ACTS = {
  block_dig: (params) => BLOCK_DIG_ACTS.has(params.status),
  block_place: () => true,
  use_entity: () => true,
  use_item: () => true
}

function gate (bot, owner) {
  let digger = null
  bot.once('login', () => { // mineflayer's digging plugin defines bot.dig when the bot is injected
    const dig = bot.dig
    bot.dig = function () { digger = owner(); return dig.apply(this, arguments) }
  })
  const write = bot._client.write
  bot._client.write = function (name, params) {
    if (ACTS[name] && ACTS[name](params)) {
      const run = owner()
      if (!run || !run.active || (name === 'block_dig' && DIGGING.has(params.status) && digger !== run)) return
    }
    return write.apply(this, arguments)
  }
}

module.exports = { gate }
