'use strict'
// Nothing acts on the world for a run that is not the current one. Stopping settles a run at once
// (run.js), but mineflayer keeps going with what it had started: bot.dig and bot.activateBlock first
// turn the head at 3 rad/s and only then send their packet, a dig's finish is sent from a timer, and
// the next run's first dig cancels the dig mineflayer still holds. So every packet that acts carries
// the run whose code led to it: agent code runs inside `within(run, ...)` (Node's AsyncLocalStorage),
// and whatever it awaits, its timers and the promises of the mineflayer methods it called, keep that
// run as their context. `gate(bot, owner)` drops an acting packet (BOUND) whose run is not the current
// one (`owner()`) or has stopped. A packet written outside any run's context (the bot's own physics and
// plugins, halt() cleaning up) is dropped only when it changes the world (ACTS) while no run is active.
// `clearLeftovers()`, called between runs, forgets a dig mineflayer still holds: its cancel is written
// while no run is active and dropped, so the server never hears of it.
const { AsyncLocalStorage } = require('async_hooks')

const context = new AsyncLocalStorage()
const BLOCK_DIG_ACTS = new Set([0, 1, 2, 3, 4]) // start, cancel, finish, drop stack, drop item (5 = release a used item)
// packets a run's code makes the player send: the world's and its own (equip, windows, chat, swings)
const BOUND = new Set(['block_dig', 'block_place', 'use_entity', 'use_item', 'held_item_slot', 'window_click',
  'close_window', 'chat', 'arm_animation', 'set_creative_slot', 'entity_action'])
const ACTS = {
  block_dig: (params) => BLOCK_DIG_ACTS.has(params.status),
  block_place: () => true,
  use_entity: () => true,
  use_item: () => true
}

function within (run, fn) {
  return context.run(run, fn)
}

function gate (bot, owner) {
  const write = bot._client.write
  bot._client.write = function (name, params) {
    if (BOUND.has(name)) {
      const caller = context.getStore()
      const run = owner()
      const live = Boolean(run && run.active)
      if (caller !== undefined ? caller !== run || !live : !live && ACTS[name] && ACTS[name](params)) return
    }
    return write.apply(this, arguments)
  }
}

function clearLeftovers (bot) {
  try { if (bot.targetDigBlock) bot.stopDigging() } catch (_) {}
}

module.exports = { gate, within, clearLeftovers }
