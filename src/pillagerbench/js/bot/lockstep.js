'use strict'
// This bot on the lockstep clock (js/clock/game_clock.js, js/server/plugins/lockstep.js): it joins the
// server's clock when it logs in, and for each tick the server sends it advances 50 ms of game time
// (mineflayer's physics step, the timers of its plugins and of agent code, the promises they settle)
// and then says it has done the tick, after the packets it sent meanwhile. Until the first tick comes,
// its game time follows the wall clock (mineflayer loads its plugins from a timer before logging in).
const clock = require('../clock/game_clock')
const { CHANNELS, tickData, tickOf } = require('../clock/channels')

const FREE_MS = 10

function attach (bot) {
  if (!clock.lockstep) return
  const client = bot._client
  let chain = Promise.resolve()
  let free = clock.real.setInterval(() => { chain = chain.then(() => clock.advance(FREE_MS)) }, FREE_MS)
  client.on('custom_payload', ({ channel, data }) => {
    if (channel !== CHANNELS.TICK) return
    if (free) { clock.real.clearInterval(free); free = null }
    const tick = tickOf(data)
    chain = chain
      .then(() => clock.advance(clock.TICK_MS))
      .catch(() => {}) // a timer that threw was reported by its own handler; the tick is still done
      .then(() => client.write('custom_payload', { channel: CHANNELS.DONE, data: tickData(tick) }))
  })
  client.on('end', () => { if (free) clock.real.clearInterval(free) })
  client.once('login', () => client.write('custom_payload', { channel: CHANNELS.JOIN, data: Buffer.alloc(0) }))
}

module.exports = { attach }
