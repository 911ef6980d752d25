'use strict'
// The lockstep coordinator (clock=lockstep; js/clock/game_clock.js): game tick N+1 begins only when
// every bot on the game clock has done tick N and nothing holds the clock (a player's LLM call in
// flight: the `hold` and `release` ops). Beginning a tick advances the server's own game time by
// 50 ms (flying-squid's tick loop, our plugins' timers), then sends each bot the tick.
// Pacing: `speed` ticks at that multiple of real time; unpaced (null), as fast as the slowest bot.
// Every PUSH_EVERY ticks the tick is pushed to the control channel (Python's game clock).
// During a game (`clock` op, `game: true`) a bot whose run has ended holds the clock (`idle:NAME`) until
// its next run begins or its team releases it (Python, TeamContext.sleep): a team's next program then
// starts at the tick its last one ended, however long Python took; held for IDLE_LIMIT_MS of wall time
// at most (a team that waits some other way), it lets go. A game begins with every bot idle (the match
// releases those no team plays).
// clock=real: the ops answer the server's tick and refuse to hold.
const clock = require('../../clock/game_clock')
const { CHANNELS, CLOCK_CHANNELS, tickData, tickOf } = require('../../clock/channels')
const { ControlError } = require('../util')

const PUSH_EVERY = 4
// A team that waits other than through its context (TeamContext.sleep) would hold the world for ever.
// Each let-go is counted (`let_go` in the clock's state) and the match records it: the world went on at
// a tick the wall clock chose, so that game may not repeat under its seed.
const IDLE_LIMIT_MS = 5000

module.exports.server = function (serv, settings = {}) {
  serv.pb = serv.pb || {}
  const lock = {
    serv,
    idleLimitMs: settings.idleLimitMs ?? IDLE_LIMIT_MS,
    members: new Map(), // a bot's connection -> the last tick it has done
    holds: new Map(), // who -> count
    waiters: [], // [tick, resolve]
    // holdsOf: how many times holds were dropped (each whistle, each game's start): a rest begun before
    // neither takes nor gives back a hold after (see rest)
    state: { tick: 0, speed: 1, anchor: null, busy: false, scheduled: false, game: false, gameStart: 0, holdsOf: 0 },
    idleTimers: new Map(), // idle:NAME -> the wall-clock timer that lets go of it
    letGo: {}, // idle:NAME -> how many times this game the server let go of it
    // idle:NAME of the players resting (a `rest` in progress). Python's `rest` (the control channel) can
    // reach the server before the bot's IDLE for the run that just ended (its game connection): that late
    // IDLE must not hold the world again until the rest is over.
    resting: new Set(),
    retired: new Set(), // idle:NAME of the players that hold nothing more this game (see retire)
    freed: new Set(), // idle:NAME freed before the IDLE of its ended run came (see free): that IDLE is ignored
    inbox: new Map(), // a bot's connection -> what it sent since the last tick, to be read at the next
    answers: [] // the answers of waits whose tick has come, until every bot has done that tick
  }
  serv.pb.clock = { ...gameOps(lock), ...holdOps(lock), ...botOps(lock) }
  if (clock.lockstep) {
    serv._server.on('connection', (client) => listen(serv, client))
    schedule(lock, 0)
  }
}

// `lock`: the coordinator's state, made in the server's closure above.
const botsDone = (lock) => [...lock.members.values()].every(done => done >= lock.state.tick)
const ready = (lock) => lock.holds.size === 0 && botsDone(lock)

// A wait is answered (to Python) only once every bot has done the tick it waited for: what Python does
// next (a team's next run, a step of the game master's) then reaches each bot between this tick and
// the next, never before the bot has received this tick, where it would act one tick early.
function answer (lock, fn) {
  if (botsDone(lock)) fn()
  else lock.answers.push(fn)
}
function flushAnswers (lock) {
  if (lock.answers.length && botsDone(lock)) for (const fn of lock.answers.splice(0)) fn()
}

function schedule (lock, ms) {
  const state = lock.state
  if (state.scheduled) return
  state.scheduled = true
  const go = () => { state.scheduled = false; step(lock) }
  if (ms > 0) clock.real.setTimeout(go, ms)
  else clock.real.setImmediate(go)
}

async function step (lock) {
  const { serv, state, members } = lock
  if (state.busy) return
  if (!ready(lock)) { state.anchor = null; return } // waiting: pace anew from the tick that frees it
  if (state.speed !== null) {
    const now = clock.real.now()
    if (!state.anchor) state.anchor = { real: now, tick: state.tick }
    const wait = state.anchor.real + (state.tick + 1 - state.anchor.tick) * clock.TICK_MS / state.speed - now
    if (wait > 1) return schedule(lock, wait)
  }
  state.busy = true
  const sockets = [...members.keys()].map(c => c.socket).filter(Boolean)
  for (const socket of sockets) socket.cork() // what a tick sends each bot: one write, not one per packet
  try {
    if (state.game && serv.pb.reseed) serv.pb.reseed(state.tick + 1 - state.gameStart)
    readPackets(lock)
    state.tick++
    await clock.advance(clock.TICK_MS)
    for (const client of members.keys()) {
      try { client.write('custom_payload', { channel: CHANNELS.TICK, data: tickData(state.tick) }) } catch (_) {}
    }
    if (state.tick % PUSH_EVERY === 0) serv.emit('control_event', { event: 'clock', tick: state.tick })
    answerDue(lock)
  } finally {
    for (const socket of sockets) socket.uncork()
    state.busy = false
  }
  schedule(lock, 0)
}

function answerDue (lock) { // every wait whose tick has come
  const waiters = lock.waiters
  for (let i = waiters.length - 1; i >= 0; i--) {
    if (waiters[i][0] <= lock.state.tick) waiters.splice(i, 1)[0][1]()
  }
}

// What the bots sent since the last tick, read now, bot by bot in the order of their names: the
// order in which the four connections happen to be read never decides who picked an item up first.
function readPackets (lock) {
  const inbox = lock.inbox
  const order = [...inbox.keys()].sort((a, b) => String(a.username).localeCompare(String(b.username)))
  for (const client of order) for (const fn of inbox.get(client).splice(0)) read(fn)
}
function read (fn) { // as the connection would have: a handler that throws is reported, the tick goes on
  try { fn() } catch (err) { console.error(`[clock] a packet handler threw: ${err && err.stack ? err.stack : err}`) }
}

// A game begins: what the server does every so many ticks (crop growth every 20, health regeneration)
// counts from here (serv.pb.tick0), not from whenever the server started, so that the same seed gives
// the same game (serv.tickCount itself only ever goes on). Not the hens' laying cycles (plugins/mobs.js):
// they run from the arena's build, as on the real clock, and may lay before the game begins.
function beginGame (lock) {
  const state = lock.state
  state.gameStart = state.tick
  state.gameEnd = null
  for (const who of Object.keys(lock.letGo)) delete lock.letGo[who]
  lock.serv.pb.tick0 = lock.serv.tickCount
}

function describeClock (lock) {
  const { serv, state, holds, members, letGo } = lock
  return { mode: clock.lockstep ? 'lockstep' : 'real', tick: clock.lockstep ? state.tick : serv.tickCount, speed: state.speed, holds: [...holds.keys()], bots: members.size, let_go: { ...letGo } }
}
const lockstepOnly = (op) => { if (!clock.lockstep) throw new ControlError(`op ${op} needs clock=lockstep (this server runs on the real clock)`) }

// serv.pb.clock's ops of the game: its state, its pace, its start and its whistle.
function gameOps (lock) {
  const { state, holds, waiters, idleTimers, resting, retired, freed } = lock
  const describe = () => describeClock(lock)
  return {
    describe,
    // The tick of the game in progress (0 at its start) on the lockstep clock, and after its whistle the
    // whistle's (the clock runs on then at whatever pace: what happens after is not the game's); null on
    // the real clock.
    gameTick: () => (clock.lockstep ? (state.game ? state.tick : state.gameEnd ?? state.tick) - state.gameStart : null),
    whistled: () => clock.lockstep && !state.game && state.gameEnd !== null && state.gameEnd !== undefined,
    inGame: () => state.game,
    configure ({ speed, unpaced, drop_holds: dropHolds, game }) {
      if (dropHolds === true) { // the whistle: no hold outlives its game, not even one still to come
        state.holdsOf++
        holds.clear()
        resting.clear()
        retired.clear()
        freed.clear()
        for (const w of waiters) w[2] = null
        for (const t of idleTimers.values()) clock.real.clearTimeout(t)
        idleTimers.clear()
      }
      if (game === false && state.game) state.gameEnd = state.tick
      if (game === false) state.game = false
      if (game === true && !clock.lockstep) state.game = true
      if (speed !== undefined) {
        if (!(speed > 0)) throw new ControlError(`speed must be a multiple of real time above 0, got ${JSON.stringify(speed)}`)
        state.speed = speed
      }
      if (unpaced === true) state.speed = null
      state.anchor = null
      if (clock.lockstep) schedule(lock, 0)
      if (game === true && clock.lockstep) return this.startGame()
      return describe()
    },
    // A game begins once no chunks are being sent to anyone and every bot has done a tick since, so that
    // each bot begins with all the chunks around it (how many had arrived depended on how many ticks the
    // reset took on the wall clock, and a bot short of a chunk searched its paths differently). Then every
    // bot is idle (held) until its first run, and the answer waits for every bot (see answer()).
    async startGame () {
      await lock.serv.pb.squareChunks?.() // js/server/plugins/chunks.js
      await new Promise(resolve => waiters.push([state.tick + 1, () => answer(lock, resolve), null]))
      state.game = true
      beginGame(lock)
      for (const client of lock.members.keys()) this.idle(client)
      return describe()
    }
  }
}

// serv.pb.clock's holds: Python's (hold, release, wait_tick) and the players' rests, retirements and frees.
function holdOps (lock) {
  const { state, holds, waiters, resting, retired, freed } = lock
  return {
    hold (who) {
      lockstepOnly('hold')
      holds.set(who, (holds.get(who) || 0) + 1)
      return state.tick
    },
    release (who) {
      lockstepOnly('release')
      const n = (holds.get(who) || 0) - 1
      if (n > 0) holds.set(who, n)
      else this.releaseAll(who) // an idle hold's wall-clock limit goes with it
      schedule(lock, 0)
      return state.tick
    },
    // Answer at `tick` (at once if it has come); with `who`, hold the clock for it there (a step of the
    // game master's or a score sample, done exactly at that tick; then `release`).
    // With `release`, one hold of that holder goes once the wait is in place.
    waitTick (tick, who, release) {
      lockstepOnly('wait_tick')
      const reached = (holder) => { if (holder) holds.set(holder, (holds.get(holder) || 0) + 1); return state.tick }
      const reply = (holder, resolve) => { const t = reached(holder); answer(lock, () => resolve(t)) }
      const got = tick <= state.tick
        ? new Promise(resolve => reply(who, resolve))
        : new Promise(resolve => { const w = [tick, () => reply(w[2], resolve), who || null]; waiters.push(w) })
      if (release) this.release(release)
      return got
    },
    // The players' idle holds go now and come back `ticks` later, on that tick exactly (atomic: the
    // clock cannot pass it before the wait is in place, for it is held until the release). A rest the
    // whistle cut short still answers at its tick, but gives nothing back: its tick could fall in the
    // next game (between games the clock keeps real time's pace, so when depended on the wall clock),
    // where it ended that game's own rest of the player and held the world idle until the server let
    // go (then after 5 s of wall time: a stop at each game's start but the first, with protocol=upstream).
    rest (players, ticks) {
      lockstepOnly('rest')
      const names = players.map(name => `idle:${name}`)
      const holdsOf = state.holdsOf
      const back = new Promise(resolve => waiters.push([state.tick + Math.max(0, ticks), () => {
        const mine = state.holdsOf === holdsOf
        if (mine) for (const who of names) resting.delete(who)
        for (const who of names) if (mine && state.game) this.holdIdle(who)
        const t = state.tick
        answer(lock, () => resolve(t))
      }, null]))
      for (const who of names) { resting.add(who); this.releaseAll(who) }
      if (ticks <= 0) answerDue(lock)
      return back
    },
    // Their team's play is over, or the game's time is (with scoring=upstream the game plays on past the
    // whistle to upstream's last sample): they hold nothing more until the game ends (the whistle's
    // drop_holds forgets it), not even as a run or a rest of theirs ends. Held idle, each would stop the
    // world until the server let go (do_nothing's players, every such game; aggressive's player whose
    // last rest ended at the whistle).
    retire (players) {
      lockstepOnly('retire')
      for (const who of players.map(name => `idle:${name}`)) { retired.add(who); this.releaseAll(who) }
      return state.tick
    },
    // Players whose last run has ended hold the world no more (an outside agent's seat: its team holds the
    // world itself while the agent thinks, or lets it go on for its other players): a hold is released now;
    // one still to come (the run's IDLE, on the bot's own connection, may come after this op) is ignored.
    free (players) {
      lockstepOnly('free')
      for (const who of players.map(name => `idle:${name}`)) {
        if (holds.has(who)) this.releaseAll(who)
        else freed.add(who)
      }
      return state.tick
    }
  }
}

// serv.pb.clock's bots: their connections joining, doing ticks, going idle and busy, leaving.
function botOps (lock) {
  const { state, members, holds, idleTimers, letGo, resting, retired, freed, inbox } = lock
  return {
    idle (client) {
      if (process.env.PB_TRACE) console.error(`[clock] ${state.tick} idle ${client.username} game=${state.game}`)
      if (freed.delete(`idle:${client.username}`)) return
      if (!state.game || !members.has(client) || resting.has(`idle:${client.username}`)) return
      this.holdIdle(`idle:${client.username}`)
    },
    holdIdle (who) { // held until its next run or a rest; after IDLE_LIMIT_MS of wall time it lets go
      if (holds.has(who) || retired.has(who)) return
      holds.set(who, 1)
      idleTimers.set(who, clock.real.setTimeout(() => {
        idleTimers.delete(who)
        letGo[who] = (letGo[who] || 0) + 1
        console.error(`[clock] ${who} let go after ${lock.idleLimitMs} ms of wall time: its team neither ran nor rested it`)
        this.releaseAll(who)
      }, lock.idleLimitMs))
    },
    busy (client) {
      if (process.env.PB_TRACE) console.error(`[clock] ${state.tick} busy ${client.username}`)
      freed.delete(`idle:${client.username}`) // (an IDLE before this BUSY has come: the connection keeps order)
      this.releaseAll(`idle:${client.username}`)
    },
    releaseAll (who) {
      const t = idleTimers.get(who)
      if (t) { clock.real.clearTimeout(t); idleTimers.delete(who) }
      if (holds.delete(who)) schedule(lock, 0)
    },
    join (client) {
      members.set(client, state.tick)
      inbox.set(client, queueing(client))
      schedule(lock, 0)
    },
    done (client, tick) {
      if (!members.has(client) || tick === null) return
      members.set(client, Math.max(members.get(client), tick))
      flushAnswers(lock)
      schedule(lock, 0)
    },
    leave (client) {
      for (const fn of (inbox.get(client) || []).splice(0)) read(fn)
      inbox.delete(client)
      resting.delete(`idle:${client.username}`)
      this.releaseAll(`idle:${client.username}`)
      if (members.delete(client)) { flushAnswers(lock); schedule(lock, 0) }
    }
  }
}

// From now on the packets a bot sends reach flying-squid's handlers only when the queue returned is
// read (at the next tick); the clock's own packets are read at once.
function queueing (client) {
  const queue = []
  const emit = client.emit
  let later = false // the packet being emitted (events 'packet', its name, 'raw.NAME', 'raw') waits
  client.emit = function (event, ...args) {
    if (event === 'packet') later = !(args[1].name === 'custom_payload' && CLOCK_CHANNELS.has(args[0].channel))
    const name = args[1]?.name
    const wait = later && (event === 'packet' || event === 'raw' || event === name || event === `raw.${name}`)
    if (event === 'raw') later = false
    if (!wait) return emit.call(this, event, ...args)
    queue.push(() => emit.call(this, event, ...args))
    return true
  }
  return queue
}

// Each connection, from its first packet on (a bot joins as it logs in, before flying-squid has made it a player).
function listen (serv, client) {
  client.on('custom_payload', ({ channel, data }) => {
    if (channel === CHANNELS.JOIN) serv.pb.clock.join(client)
    else if (channel === CHANNELS.DONE) serv.pb.clock.done(client, tickOf(data))
    else if (channel === CHANNELS.IDLE) serv.pb.clock.idle(client)
    else if (channel === CHANNELS.BUSY) serv.pb.clock.busy(client)
  })
  client.on('end', () => serv.pb.clock.leave(client))
}
