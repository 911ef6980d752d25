'use strict'
// This bot on the lockstep clock (js/clock/game_clock.js, js/server/plugins/lockstep.js): it joins the
// server's clock when it logs in, and for each tick the server sends it advances 50 ms of game time
// (mineflayer's physics step, the timers of its plugins and of agent code, the promises they settle)
// and then says it has done the tick, after the packets it sent meanwhile. Until the first tick comes,
// its game time follows the wall clock (mineflayer loads its plugins from a timer before logging in).
const clock = require('../clock/game_clock')
const { CHANNELS, CLOCK_CHANNELS, tickData, tickOf } = require('../clock/channels')

const FREE_MS = 10
// mineflayer's 50 ms physics timer starts at login. At its first tick the bot moves its game time on
// so that the physics step comes PHASE_MS after each tick's start in every run: runs begin on a tick's
// start, so what they time in whole ticks (waits, digs) never coincides with a physics step.
const PHASE_MS = 25
const TRACE = /\bticks\b/.test(process.env.PB_TRACE || '') // PB_TRACE=ticks: where the bot is after each tick
const state = { tick: null } // the server's last tick this bot has begun (null: not on the clock)

function attach (bot) {
  if (!clock.lockstep) return
  // mineflayer injects its plugins from a zero-delay timer set in createBot. On the game clock that
  // timer waited for the first free advance, and the server's first packets could come before it: an
  // `update_health` read before the health plugin listened, the bot never spawned (3 starts in about
  // 150, two matches at once). Run it now, before any packet can be read.
  clock.runDue()
  const client = bot._client
  sendWithinTicks(client)
  if (TRACE) watch(bot)
  let chain = Promise.resolve()
  let free = clock.real.setInterval(() => { chain = chain.then(() => clock.advance(FREE_MS)) }, FREE_MS)
  let loginAt = null
  client.once('login', () => { loginAt = clock.now() })
  client.on('custom_payload', ({ channel, data }) => {
    if (channel !== CHANNELS.TICK) return
    if (free) {
      clock.real.clearInterval(free)
      free = null
      onBoundaries(client)
      chain = chain.then(() => clock.advance(phaseShift(loginAt)))
    }
    const tick = tickOf(data)
    state.tick = tick
    chain = chain
      .then(settled) // what the packets before the tick set off is done before the tick begins
      .then(() => { client.socket.cork(); return clock.advance(clock.TICK_MS) }) // the tick's packets: one write
      .catch(() => {}) // a timer that threw was reported by its own handler; the tick is still done
      .then(() => { if (TRACE) trace(bot, tick) })
      .then(() => {
        client.write('custom_payload', { channel: CHANNELS.DONE, data: tickData(tick) })
        client.socket.uncork()
      })
  })
  client.on('end', () => { if (free) clock.real.clearInterval(free) })
  client.once('login', () => client.write('custom_payload', { channel: CHANNELS.JOIN, data: Buffer.alloc(0) }))
}

// One turn of the event loop: the promises that the packets read before a tick settled, and the
// stream callbacks still to deliver them, all run before the tick begins. Without it they ran before
// or inside the tick depending on whether the packets came in one read with the tick or in an earlier
// one (TCP's choice): inside, what they sent went out a tick early and what they searched counted
// against that tick's budget (a path search ended two ticks apart in two runs of one seed).
const settled = () => new Promise(resolve => clock.real.setImmediate(resolve))

// How far to move game time on so that a timer of 50 ms set at `since` fires PHASE_MS into each tick.
function phaseShift (since) {
  if (since === null) return 0
  const tick = clock.TICK_MS
  return (((since + PHASE_MS - clock.now()) % tick) + tick) % tick
}

// What the server sends reaches the bot's handlers between two ticks, never within one: the server
// writes what another bot did during tick N (a block dug) while this bot may be doing tick N, and would
// land at any moment of it. The server sends tick N+1 after all of them, so they all land before it.
function onBoundaries (client) {
  const emit = client.emit
  client.emit = function (...args) {
    clock.atBoundary(() => emit.apply(this, args))
    return true
  }
}

// What the bot sends between two ticks (a run begun or stopped from Python, an answer to the server)
// goes out as the next tick begins: the server reads it with that tick's packets, not at whatever
// moment of its own next tick it would arrive. The clock's own packets go at once. Installed before
// gate.js's, which must judge a packet when it is written, in the context of whoever wrote it.
function sendWithinTicks (client) {
  const write = client.write
  client.write = function (name, params) {
    const now = state.tick === null || clock.advancing || (name === 'custom_payload' && CLOCK_CHANNELS.has(params.channel))
    if (now) return write.call(this, name, params)
    clock.atNextTick(() => write.call(this, name, params))
  }
}

const seen = { packets: [], physics: 0 } // since the last trace
function trace (bot, tick) { // for benchmarks/lockstep_determinism.py: the first tick two runs part
  const e = bot.entity
  if (!e) return
  const f = (v) => v.toFixed(6)
  const got = seen.packets.splice(0).join(',')
  console.error(`[tick] ${tick} ${f(e.position.x)} ${f(e.position.y)} ${f(e.position.z)} ${f(e.yaw)} ${f(e.pitch)} ${f(e.velocity.x)} ${f(e.velocity.y)} ${f(e.velocity.z)} c${columns(bot)} p${seen.physics} ${got}`)
  seen.physics = 0
}
const columns = (bot) => { try { return bot.world.async.getColumns().length } catch (_) { return -1 } }
function watch (bot) {
  bot.on('physicsTick', () => seen.physics++)
  bot._client.on('packet', (_, meta) => { if (meta.name !== 'custom_payload') seen.packets.push(meta.name) })
}

// A run has begun (BUSY) or ended (IDLE): during a game an ended run holds the clock until the next
// (js/server/plugins/lockstep.js).
function said (bot, channel) {
  if (clock.lockstep) bot._client.write('custom_payload', { channel, data: Buffer.alloc(0) })
}

module.exports = { attach, tick: () => state.tick, busy: (bot) => said(bot, CHANNELS.BUSY), idle: (bot) => said(bot, CHANNELS.IDLE) }
