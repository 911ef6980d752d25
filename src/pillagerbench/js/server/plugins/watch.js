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

module.exports.server = function (serv) {
  let child = null
  let inFlight = 0
  let resync = false
  let center = [0, 4, 0]
  let timer = null
  const state = { title: '', episode: null, t: null, length: null, scores: {}, sides: {} }

  function send (msg, droppable) {
    if (!child || !child.connected) return
    if (inFlight >= MAX_IN_FLIGHT) {
      if (!droppable) resync = true
      return
    }
    inFlight++
    try {
      child.send(msg, () => { inFlight-- })
    } catch (err) {
      inFlight--
    }
  }

  async function sendColumns () {
    resync = false
    const cx = Math.floor(center[0] / 16); const cz = Math.floor(center[2] / 16)
    send({ type: 'reset', center }, false)
    for (let x = cx - RADIUS; x <= cx + RADIUS; x++) {
      for (let z = cz - RADIUS; z <= cz + RADIUS; z++) {
        const column = await serv.overworld.getColumn(x, z)
        if (column) send({ type: 'column', x, z, chunk: column.toJson() }, false)
        await new Promise(resolve => setImmediate(resolve)) // one column per turn: ticks go first
      }
    }
  }

  function frame () {
    if (resync && inFlight === 0) { sendColumns().catch(err => serv.emit('pluginError', err, 'watch columns')); return }
    const list = []
    for (const p of serv.players) {
      if (p.world !== serv.overworld) continue
      list.push([p.id, 'player', p.username, p.position.x, p.position.y, p.position.z, (p.yaw || 0) * 360 / 256])
    }
    for (const e of Object.values(serv.entities)) {
      if (e.type === 'mob' && !e.dead) list.push([e.id, e.name, null, e.position.x, e.position.y, e.position.z, 0])
      else if (e.type === 'object' && e.itemId && !e.collected) list.push([e.id, 'item', null, e.position.x, e.position.y, e.position.z, 0])
    }
    send({ type: 'entities', list }, true)
  }

  serv.pb.watch = {
    // Start the viewer process on host:port; resolves to its URL, rejects with a one-line reason.
    start: ({ host = '127.0.0.1', port = 0 }) => new Promise((resolve, reject) => {
      child = fork(path.join(__dirname, '..', '..', 'watch', 'main.js'), [JSON.stringify({ host, port, version: serv.supportedVersion || '1.16.5' })], {
        stdio: ['ignore', 'inherit', 'inherit', 'ipc'], serialization: 'json'
      })
      let started = false
      child.on('message', (msg) => {
        if (msg.type === 'listening' && !started) {
          started = true
          serv.pb.listenBlocks((x, y, z, stateId) => send({ type: 'block', x, y, z, stateId }, false))
          timer = setInterval(frame, FRAME_MS)
          sendColumns().catch(err => serv.emit('pluginError', err, 'watch columns'))
          resolve(`http://${host}:${msg.port}/`)
        } else if (msg.type === 'failed' && !started) {
          started = true
          reject(new Error(msg.error))
        }
      })
      child.on('exit', (code) => {
        if (timer) clearInterval(timer)
        timer = null
        child = null
        if (!started) reject(new Error(`the live view process ended before listening (exit code ${code})`))
        else console.error(`[watch] the live view process ended (exit code ${code}); the game goes on without it`)
      })
    }),
    // The scoreboard and what to look at: {center, title, episode, t, length, scores, sides}.
    update: (args) => {
      for (const key of Object.keys(state)) if (key in args) state[key] = args[key]
      if (Array.isArray(args.center)) {
        if (args.center.length !== 3 || !args.center.every(Number.isFinite)) throw new ControlError('center must be [x, y, z]')
        const moved = args.center.some((v, i) => Math.abs(v - center[i]) > 8)
        center = args.center
        if (moved && child) sendColumns().catch(err => serv.emit('pluginError', err, 'watch columns'))
      }
      send({ type: 'state', state, center }, true)
      return Boolean(child)
    },
    stop: () => { if (child) child.kill() }
  }
}
