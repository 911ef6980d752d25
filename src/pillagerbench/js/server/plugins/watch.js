'use strict'
// The live view (`watch=PORT`): a child process (js/watch/main.js) serves prismarine-viewer and a
// scoreboard to browsers; this plugin feeds it over IPC from the server's own state: the arena's
// chunk columns, every block written, and players, items and mobs 5 times a second. The viewer is
// not a player: nothing of it enters the world, the player list or any observation. It never
// slows the game: messages the child has not taken yet are bounded (MAX_IN_FLIGHT); beyond that,
// entity frames are dropped and the world is sent afresh once it has caught up; if the child dies
// the game goes on without it.
const path = require('path')
const { fork } = require('child_process')
const { ControlError } = require('../util')

const FRAME_MS = 200
const MAX_IN_FLIGHT = 64
const RADIUS = 3 // chunk columns around the centre: 7 x 7 columns, 112 blocks across

// `view`: the live view's state ({ child, inFlight, resync, center, timer, state }, made in the server's closure).
function send (view, msg, droppable) {
  if (!view.child || !view.child.connected) return
  if (view.inFlight >= MAX_IN_FLIGHT) {
    if (!droppable) view.resync = true
    return
  }
  view.inFlight++
  try {
    view.child.send(msg, () => { view.inFlight-- })
  } catch (err) {
    view.inFlight--
  }
}

async function sendColumns (serv, view) {
  view.resync = false
  const center = view.center
  const cx = Math.floor(center[0] / 16); const cz = Math.floor(center[2] / 16)
  send(view, { type: 'reset', center }, false)
  for (let x = cx - RADIUS; x <= cx + RADIUS; x++) {
    for (let z = cz - RADIUS; z <= cz + RADIUS; z++) {
      const column = await serv.overworld.getColumn(x, z)
      if (column) send(view, { type: 'column', x, z, chunk: column.toJson() }, false)
      await new Promise(resolve => setImmediate(resolve)) // one column per turn: ticks go first
    }
  }
}

function frame (serv, view) {
  if (view.resync && view.inFlight === 0) { sendColumns(serv, view).catch(err => serv.emit('pluginError', err, 'watch columns')); return }
  const list = []
  for (const p of serv.players) {
    if (p.world !== serv.overworld) continue
    list.push([p.id, 'player', p.username, p.position.x, p.position.y, p.position.z, (p.yaw || 0) * 360 / 256])
  }
  for (const e of Object.values(serv.entities)) {
    if (e.type === 'mob' && !e.dead) list.push([e.id, e.name, null, e.position.x, e.position.y, e.position.z, 0])
    else if (e.type === 'object' && e.itemId && !e.collected) list.push([e.id, 'item', null, e.position.x, e.position.y, e.position.z, 0])
  }
  send(view, { type: 'entities', list }, true)
}

// Start the viewer process on host:port; resolves to its URL, rejects with a one-line reason.
function start (serv, view, { host = '127.0.0.1', port = 0 }) {
  return new Promise((resolve, reject) => {
    const child = view.child = fork(path.join(__dirname, '..', '..', 'watch', 'main.js'), [JSON.stringify({ host, port, version: serv.supportedVersion || '1.16.5' })], {
      stdio: ['ignore', 'inherit', 'inherit', 'ipc'], serialization: 'json'
    })
    let started = false
    child.on('message', (msg) => {
      if (msg.type === 'listening' && !started) {
        started = true
        serv.pb.listenBlocks((x, y, z, stateId) => send(view, { type: 'block', x, y, z, stateId }, false))
        view.timer = setInterval(() => frame(serv, view), FRAME_MS)
        sendColumns(serv, view).catch(err => serv.emit('pluginError', err, 'watch columns'))
        resolve(`http://${host}:${msg.port}/`)
      } else if (msg.type === 'failed' && !started) {
        started = true
        reject(new Error(msg.error))
      }
    })
    child.on('exit', (code) => {
      if (view.timer) clearInterval(view.timer)
      view.timer = null
      view.child = null
      if (!started) reject(new Error(`the live view process ended before listening (exit code ${code})`))
      else console.error(`[watch] the live view process ended (exit code ${code}); the game goes on without it`)
    })
  })
}

// The scoreboard and what to look at: {center, title, episode, t, length, scores, sides}.
function update (serv, view, args) {
  const state = view.state
  for (const key of Object.keys(state)) if (key in args) state[key] = args[key]
  if (Array.isArray(args.center)) {
    if (args.center.length !== 3 || !args.center.every(Number.isFinite)) throw new ControlError('center must be [x, y, z]')
    const moved = args.center.some((v, i) => Math.abs(v - view.center[i]) > 8)
    view.center = args.center
    if (moved && view.child) sendColumns(serv, view).catch(err => serv.emit('pluginError', err, 'watch columns'))
  }
  send(view, { type: 'state', state, center: view.center }, true)
  return Boolean(view.child)
}

module.exports.server = function (serv) {
  const view = {
    child: null,
    inFlight: 0,
    resync: false,
    center: [0, 4, 0],
    timer: null,
    state: { title: '', episode: null, t: null, length: null, scores: {}, sides: {} }
  }

  serv.pb.watch = {
    start: (options) => start(serv, view, options),
    update: (args) => update(serv, view, args),
    stop: () => { if (view.child) view.child.kill() }
  }
}
