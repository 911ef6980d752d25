'use strict'
// The game clock of one Node process (the arena server or a bot).
// clock=real: nothing changes; every timer and clock reading is the wall clock.
// clock=lockstep: everything this process reads as time (setTimeout, setInterval, Date, performance.now,
// hence mineflayer's physics, dig timing and pathfinder limits, flying-squid's tick loop, the checks that
// read Date.now) becomes game time, which moves only when `advance(ms)` is called: by the server's
// coordinator (js/server/lockstep.js) once every bot has done the tick, and in a bot when the server's
// tick packet arrives (js/bot/lockstep.js). The mechanism is @sinonjs/fake-timers, installed before
// anything else is loaded; its timers keep the async context of whoever set them (gate.js relies on it).
// What must stay on the wall clock (heartbeats, the pacing of the clock itself, a busy loop's limit,
// which vm enforces natively) uses `real`.
const { AsyncResource } = require('async_hooks')
const timers = require('timers')

const TICK_MS = require('./tick.json').ms // declared once (Python reads it too)
const real = {
  setTimeout: globalThis.setTimeout,
  clearTimeout: globalThis.clearTimeout,
  setInterval: globalThis.setInterval,
  clearInterval: globalThis.clearInterval,
  setImmediate: globalThis.setImmediate,
  now: performance.now.bind(performance)
}

let fake = null
let advancing = false
const deferred = [] // what came from outside during an advance, to be done at its end
const nextTick = [] // what is to be done as the next advance begins

// Do `fn` between two ticks: now if game time stands still, else when the advance in progress ends.
// Requests from outside the process (the control channel, a bot's stdin) come at any moment of the
// wall clock, and fake-timers lets the event loop turn between the timers of one advance: this keeps
// every outside input on a tick boundary.
function atBoundary (fn) {
  if (advancing) deferred.push(fn)
  else fn()
}

// Do `fn` as the next tick begins, before its timers (on the real clock: now). A bot sends what it
// writes between two ticks this way (js/bot/lockstep.js).
function atNextTick (fn) {
  if (fake) nextTick.push(fn)
  else fn()
}

function install (mode) {
  if (mode !== 'lockstep' || fake) return
  const FakeTimers = require('@sinonjs/fake-timers')
  fake = FakeTimers.withGlobal(globalThis).install({
    now: 0,
    toFake: ['setTimeout', 'clearTimeout', 'setInterval', 'clearInterval', 'Date', 'performance'],
    ignoreMissingTimers: true
  })
  searchClock(fake)
  for (const target of [globalThis, timers]) { // a timer's callback runs in the async context that set it
    for (const name of ['setTimeout', 'setInterval']) {
      const set = target[name]
      if (typeof set !== 'function') continue
      target[name] = function (fn, ms, ...args) {
        return set.call(this, typeof fn === 'function' ? AsyncResource.bind(fn) : fn, ms, ...args)
      }
    }
  }
}

// Within a tick game time stands still, so code that limits its own work by the time it has spent
// (mineflayer-pathfinder's A*: `tickTimeout` ms of search per tick, `thinkTimeout` in all) would never
// stop. So each reading of performance.now() within one tick moves it on by READ_COST_MS: a search is
// then limited by how many steps it takes, the same on every machine. The readings start again at the
// tick's own time each tick (never past it). Two readings per node: the 7 ms per tick of main.js are
// 140 nodes, what the real clock's bots searched per tick when the suite's reference figures were
// measured (4 matches at once on the 2-core reference machine: medians of 109 to 139 nodes per 7 ms slice
// for the bots that search most, as fast as the machine was that hour; benchmarks/search_budget.py,
// docs/clock.md). It was 5 µs (700 nodes): five times the real clock's search.
const READ_COST_MS = 0.025
const READ_CAP_MS = TICK_MS - 1

function searchClock (clock) {
  const perf = require('perf_hooks').performance
  const fakeNow = perf.now
  let base = -1
  let spent = 0
  const now = function () {
    const t = fakeNow.call(this)
    if (t !== base) { base = t; spent = 0 } else if (spent < READ_CAP_MS) spent += READ_COST_MS
    return t + spent
  }
  perf.now = now
  if (globalThis.performance && globalThis.performance !== perf) globalThis.performance.now = now
}

// Move game time on by `ms`, running every timer due meanwhile, each at its own time, and between two
// timers the promises they settled (as fake-timers' own `tickAsync` does). We step the timers ourselves
// (`next()`, the heap's first timer: fake-timers 15.5, pinned) because `tickAsync` yields to the event
// loop with a native setTimeout, which Node makes at least 1 ms: a server tick of five timers cost
// 6 ms of waiting. `setImmediate` yields for microseconds.
const LOOP_LIMIT = 1000 // timers in one tick, as fake-timers' loopLimit: an endless chain of zero delays
const turn = () => new Promise(resolve => real.setImmediate(resolve))
const nextDue = () => { const t = fake.timerHeap && fake.timerHeap.peek(); return t ? t.callAt : null }

async function advance (ms = TICK_MS) {
  if (!fake) return
  advancing = true
  let first = null
  try {
    for (const fn of nextTick.splice(0)) fn()
    const target = fake.now + ms
    await turn()
    for (let n = 0, due = nextDue(); due !== null && due <= target; due = nextDue()) {
      if (++n > LOOP_LIMIT) throw new Error(`Aborting after running ${LOOP_LIMIT} timers in one tick, assuming an endless loop`)
      try { fake.next() } catch (err) { first = first || err }
      await turn()
    }
    if (fake.now < target) fake.tick(target - fake.now)
  } finally {
    advancing = false
    for (const fn of deferred.splice(0)) fn()
  }
  if (first) throw first
}

// Run now the timers already due (on the real clock: nothing to do; they run in the next turn anyway).
function runDue () {
  if (fake) fake.tick(0)
}

module.exports = {
  install,
  runDue,
  get advancing () { return advancing },
  advance,
  atBoundary,
  atNextTick,
  real,
  TICK_MS,
  get lockstep () { return fake !== null },
  now: () => (fake ? fake.now : real.now())
}
