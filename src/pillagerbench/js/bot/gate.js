'use strict'
// Nothing acts on the world for a run that has stopped. Stopping settles the run at once (run.js),
// but mineflayer keeps going with what it had started: bot.dig and bot.activateBlock first turn the
// head at 3 rad/s and only then send their packet, so a dig begun just before the stop would break
// its block up to a second later. `gate(bot, acting)` drops the packets that change the world (dig
// start and finish, drop items, use on a block, an entity or in the air) while `acting()` is false.
// Cancelling a dig and releasing a used item stay allowed: halt() sends them.
const BLOCK_DIG_ACTS = new Set([0, 2, 3, 4]) // start, finish, drop stack, drop item
const ACTS = {
  block_dig: (params) => BLOCK_DIG_ACTS.has(params.status),
  block_place: () => true,
  use_entity: () => true,
  use_item: () => true
}

function gate (bot, acting) {
  const write = bot._client.write
  bot._client.write = function (name, params) {
    if (ACTS[name] && ACTS[name](params) && !acting()) return
    return write.apply(this, arguments)
  }
}

module.exports = { gate }
