'use strict'
// How late this bot's physics ticks are: mineflayer moves the bot in 50 ms physics ticks driven by
// a timer of this process, so a starved CPU shows here first (late ticks, then ticks caught up in
// bursts or lost). Measured in the bot process, between `reset()` and `read()` (the match resets
// it at the start of the game and reads it at the whistle).
//   ticks         physics ticks seen
//   tick_rate     ticks per wall second (20 = none lost)
//   late_mean_ms  mean of (gap between two ticks − 50 ms), gaps shorter than 50 ms counting 0
//   late_max_ms   the largest such lateness
//   late_pct      % of ticks more than a whole tick (50 ms) late
const { TICK_MS } = require('../clock/game_clock')

class LagMeter {
  constructor (bot, now = () => performance.now()) {
    this.now = now
    this.reset()
    bot.on('physicsTick', () => this.tick())
  }

  reset () {
    this.start = this.now()
    this.last = null
    this.ticks = 0
    this.lateSum = 0
    this.lateMax = 0
    this.lateTicks = 0
  }

  tick () {
    const t = this.now()
    this.ticks++
    if (this.last !== null) {
      const late = Math.max(0, t - this.last - TICK_MS)
      this.lateSum += late
      if (late > this.lateMax) this.lateMax = late
      if (late > TICK_MS) this.lateTicks++
    }
    this.last = t
  }

  read () {
    const wall = (this.now() - this.start) / 1000
    const gaps = Math.max(1, this.ticks - 1)
    const r = (x, d = 1) => Math.round(x * 10 ** d) / 10 ** d
    return {
      ticks: this.ticks,
      wall_s: r(wall, 2),
      tick_rate: wall > 0 ? r(this.ticks / wall, 2) : null,
      late_mean_ms: r(this.lateSum / gaps, 2),
      late_max_ms: r(this.lateMax),
      late_pct: r(100 * this.lateTicks / gaps, 2)
    }
  }
}

module.exports = { LagMeter, TICK_MS }
