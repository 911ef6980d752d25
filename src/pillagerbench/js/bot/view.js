'use strict'
// A person's first-person view (the `view` op, docs/people.md): this bot serves prismarine-viewer's browser
// client (its bundle and textures, from the local package) and streams to it the world this bot sees, from
// its eyes, on a loopback port the person's page shows. Only a person's player starts it (the Python side
// asks; agents' code has no way to). prismarine-viewer is an optional package: without it the op says so.
const path = require('path')
const http = require('http')

const VIEWER_VERSION = '1.16.4' // prismarine-viewer's textures and models for 1.16 (same blocks as 1.16.5)
const VIEW_DISTANCE = 2 // chunk columns around the player: the arenas fit; each column a viewer is sent costs this bot's CPU

let started = null // the port, once listening

let loaded = null // the view's server (not yet listening), or why there is none

// Make the view's server: at start, before sandbox.harden (express mixes EventEmitter's prototype into its
// app, which the hardened bot's locked prototypes refuse). Its server side only: the whole of
// prismarine-viewer/viewer would load node-canvas, which it does not have.
function load (bot) {
  try {
    const express = require('express')
    const { WorldView } = require('prismarine-viewer/viewer/lib/worldView')
    const app = express()
    app.use('/', express.static(path.join(path.dirname(require.resolve('prismarine-viewer/package.json')), 'public')))
    const server = http.createServer(app)
    require('socket.io')(server, { path: '/socket.io' }).on('connection', (socket) => connect(bot, socket, WorldView))
    loaded = { server }
  } catch (err) {
    loaded = { error: err.code === 'MODULE_NOT_FOUND' ? 'the first-person view needs the optional package prismarine-viewer (pillagerbench setup --watch installs it)' : `the first-person view could not load: ${err.message}` }
  }
}

function connect (bot, socket, WorldView) {
  socket.emit('version', VIEWER_VERSION)
  const worldView = new WorldView(bot.world, VIEW_DISTANCE, bot.entity.position, socket)
  worldView.init(bot.entity.position).catch(() => {})
  const eyes = () => {
    socket.emit('position', { pos: bot.entity.position, yaw: bot.entity.yaw, pitch: bot.entity.pitch })
    worldView.updatePosition(bot.entity.position).catch(() => {})
  }
  eyes()
  bot.on('move', eyes)
  bot.on('forcedMove', eyes)
  worldView.listenToBot(bot)
  socket.on('disconnect', () => {
    bot.removeListener('move', eyes)
    bot.removeListener('forcedMove', eyes)
    worldView.removeListenersFromBot(bot)
  })
}

// Start the view (once) on 127.0.0.1, a free port; its port.
async function view () {
  if (!loaded) throw new Error('no first-person view for this player (not a person\'s)')
  if (loaded.error) throw new Error(loaded.error)
  if (!started) {
    const server = loaded.server
    started = new Promise((resolve, reject) => {
      server.once('error', reject)
      server.listen(0, '127.0.0.1', () => resolve(server.address().port))
    })
  }
  return started
}

module.exports = { load, view }
