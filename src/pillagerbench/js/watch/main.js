'use strict'
// The live view's process (started by the arena server's plugins/watch.js with an IPC channel):
// serves prismarine-viewer (its browser client and textures) and a scoreboard at http://host:port/,
// and streams to every browser the world it is fed: chunk columns, block updates, entities.
// It is not a Minecraft client: it never connects to the game. A browser that lags is dropped
// (it reconnects and gets the world afresh); this process lagging never holds the game up.
const path = require('path')
const http = require('http')
const express = require('express')
const { Vec3 } = require('vec3')

const settings = JSON.parse(process.argv[2] || '{}')
const VIEWER_VERSION = '1.16.4' // prismarine-viewer's textures and models for 1.16 (same blocks as 1.16.5)
const MAX_BUFFERED = 400 // packets waiting for one browser before it is dropped
const SIZES = { player: [0.6, 1.8], item: [0.25, 0.25] }
const MODELS = new Set(['player', 'cow', 'chicken', 'pig', 'sheep', 'slime']) // others are drawn as boxes

const Chunk = require('prismarine-chunk')(settings.version || '1.16.5')
const columns = new Map() // "x,z" (chunk coordinates) -> Chunk
const entities = new Map() // id -> {id, name, username, pos, yaw}
let center = [0, 4, 0]
let state = {}

const PAGE = `<!doctype html><html><head><meta charset="utf-8"><title>PillagerBench live view</title>
<style>html{overflow:hidden}html,body{height:100%;margin:0;padding:0}canvas{height:100%;width:100%;font-size:0;margin:0;padding:0}
#board{position:fixed;top:8px;left:8px;background:rgba(255,255,255,.85);font:14px system-ui,sans-serif;padding:6px 10px;border-radius:6px;z-index:2}
#board b.red{color:#c62828}#board b.blue{color:#1e4fc2}</style></head><body>
<div id="board">PillagerBench live view: waiting for the match…</div>
<script>
function show (s) {
  const el = document.getElementById('board')
  if (!s || !s.title) return
  const clock = s.t == null ? '' : ' · ' + Math.round(s.t) + ' / ' + Math.round(s.length) + ' s'
  const sides = Object.keys(s.scores || {}).map(function (k) {
    const team = (s.sides || {})[k] || ''
    return '<b class="' + k + '">' + k + (team ? ' ' + team : '') + ': ' + s.scores[k] + '</b>'
  }).join(' &nbsp; ')
  el.innerHTML = s.title + (s.episode == null ? '' : ', episode ' + s.episode) + clock + '<br>' + sides
}
function poll () { fetch('state.json').then(function (r) { return r.json() }).then(show).catch(function () {}).then(function () { setTimeout(poll, 1000) }) }
poll()
</script>
<script src="index.js"></script></body></html>`

const app = express()
app.get('/', (req, res) => res.type('html').send(PAGE))
app.get('/state.json', (req, res) => res.json({ ...state, center })) // center: where the camera looks
app.use('/', express.static(path.join(path.dirname(require.resolve('prismarine-viewer/package.json')), 'public')))
const server = http.createServer(app)
const io = require('socket.io')(server, { path: '/socket.io' })

const toEntity = (e) => ({ id: e.id, name: MODELS.has(e.name) ? e.name : undefined, username: e.username || undefined, pos: e.pos, width: (SIZES[e.name] || [0.9, 1.3])[0], height: (SIZES[e.name] || [0.9, 1.3])[1], yaw: e.yaw })
const pos = () => ({ pos: { x: center[0], y: center[1], z: center[2] }, addMesh: false })

function emitAll (event, data, volatile) {
  for (const socket of io.sockets.sockets.values()) {
    if ((socket.conn.writeBuffer?.length || 0) > MAX_BUFFERED) { socket.disconnect(true); continue }
    if (volatile) socket.volatile.emit(event, data)
    else socket.emit(event, data)
  }
}

io.on('connection', (socket) => {
  socket.emit('version', VIEWER_VERSION)
  for (const [key, chunk] of columns) {
    const [x, z] = key.split(',').map(Number)
    socket.emit('loadChunk', { x: x * 16, z: z * 16, chunk: chunk.toJson() })
  }
  socket.emit('position', pos())
  for (const e of entities.values()) socket.emit('entity', toEntity(e))
})

process.on('message', (msg) => {
  if (msg.type === 'reset') {
    for (const key of columns.keys()) {
      const [x, z] = key.split(',').map(Number)
      emitAll('unloadChunk', { x: x * 16, z: z * 16 })
    }
    columns.clear()
    center = msg.center
  } else if (msg.type === 'column') {
    const chunk = Chunk.fromJson(msg.chunk)
    columns.set(`${msg.x},${msg.z}`, chunk)
    emitAll('loadChunk', { x: msg.x * 16, z: msg.z * 16, chunk: msg.chunk })
    emitAll('position', pos())
  } else if (msg.type === 'block') {
    const chunk = columns.get(`${Math.floor(msg.x / 16)},${Math.floor(msg.z / 16)}`)
    if (!chunk) return
    chunk.setBlockStateId(new Vec3(((msg.x % 16) + 16) % 16, msg.y, ((msg.z % 16) + 16) % 16), msg.stateId)
    emitAll('blockUpdate', { pos: { x: msg.x, y: msg.y, z: msg.z }, stateId: msg.stateId })
  } else if (msg.type === 'entities') {
    const seen = new Set()
    for (const [id, name, username, x, y, z, yawDeg] of msg.list) {
      seen.add(id)
      const e = { id, name, username, pos: { x, y, z }, yaw: -yawDeg * Math.PI / 180 }
      const old = entities.get(id)
      entities.set(id, e)
      if (!old) emitAll('entity', toEntity(e))
      else if (old.pos.x !== x || old.pos.y !== y || old.pos.z !== z || old.yaw !== e.yaw) emitAll('entity', { id, pos: e.pos, yaw: e.yaw }, true)
    }
    for (const id of [...entities.keys()]) {
      if (!seen.has(id)) { entities.delete(id); emitAll('entity', { id, delete: true }) }
    }
  } else if (msg.type === 'state') {
    state = msg.state
    if (msg.center) center = msg.center
  }
})
process.on('disconnect', () => process.exit(0))

server.on('error', (err) => {
  const where = `${settings.host}:${settings.port}`
  const error = err.code === 'EADDRINUSE'
    ? `watch port ${where} is already in use (choose another with watch=PORT, or watch=0 for a free port)`
    : `the live view cannot listen on ${where}: ${err.message}`
  process.send({ type: 'failed', error }, () => process.exit(2))
})
server.listen(settings.port, settings.host, () => process.send({ type: 'listening', port: server.address().port }))
