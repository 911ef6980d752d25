'use strict'
// One run of agent code: its abort state, the promises and timers it owns, its fail counters.
// `stop()` settles everything the run is waiting on at once; whatever the agent's code does
// afterwards fails with a StopError (the run is over, so nothing it does can act any more).

class StopError extends Error {
  constructor (message = 'Stopped') {
    super(message)
    this.name = 'StopError'
  }
}

const FAIL_LIMIT = 10

class Run {
  constructor (id, { startTick = 0 } = {}) {
    this.id = id
    this.active = true
    this.reason = null
    this.startTick = startTick
    this.pending = new Set()
    this.timers = new Set()
    this.intervals = new Set()
    this.listeners = [] // [emitter, event, fn]
    this.cleanups = []
    this.fails = {}
    this.stopped = new Promise(resolve => { this._resolveStopped = resolve })
  }

  check () {
    if (!this.active) throw new StopError(this.reason || 'Stopped')
  }

  // Await `promise` unless the run stops first (then reject with a StopError).
  race (promise) {
    this.check()
    return new Promise((resolve, reject) => {
      const entry = { reject }
      this.pending.add(entry)
      Promise.resolve(promise).then(
        (v) => { this.pending.delete(entry); resolve(v) },
        (e) => { this.pending.delete(entry); reject(this.active ? e : new StopError(this.reason || 'Stopped')) })
    })
  }

  sleep (ms) {
    return this.race(new Promise(resolve => { const t = setTimeout(resolve, ms); this.cleanups.push(() => clearTimeout(t)) }))
  }

  listen (emitter, event, fn) {
    emitter.on(event, fn)
    this.listeners.push([emitter, event, fn])
    return fn
  }

  unlisten (emitter, event, fn) {
    emitter.removeListener(event, fn)
    this.listeners = this.listeners.filter(l => !(l[0] === emitter && l[1] === event && l[2] === fn))
  }

  // Count a failure of a primitive; more than FAIL_LIMIT in one run throws `message`.
  fail (counter, message) {
    this.fails[counter] = (this.fails[counter] || 0) + 1
    if (this.fails[counter] > FAIL_LIMIT) throw new Error(message)
  }

  stop (reason = 'Stopped') {
    if (!this.active) return
    this.active = false
    this.reason = reason
    const err = new StopError(reason)
    for (const p of this.pending) p.reject(err)
    this.pending.clear()
    for (const t of this.timers) clearTimeout(t)
    for (const t of this.intervals) clearInterval(t)
    this.timers.clear(); this.intervals.clear()
    for (const [emitter, event, fn] of this.listeners) emitter.removeListener(event, fn)
    this.listeners = []
    for (const fn of this.cleanups.splice(0)) { try { fn() } catch (_) {} }
    this._resolveStopped(reason)
  }
}

const isStop = (err) => err instanceof StopError || (err && err.name === 'StopError')

module.exports = { Run, StopError, isStop, FAIL_LIMIT }
