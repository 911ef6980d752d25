'use strict'
// The arena server: flying-squid on Minecraft 1.16.5 with our plugins, driven over the control
// channel (see control.js): a socket the parent passes as an inherited file descriptor (settings.controlFd). stdout and stderr are
// the server log (flying-squid also reads console commands from stdin; the parent gives it none).
// Usage: node main.js '<json settings>'   e.g. {"port": 0, "host": "127.0.0.1", "clock": "real"}
const settings = JSON.parse(process.argv[2] || '{}')
const clock = require('../clock/game_clock')
clock.install(settings.clock) // before anything reads the time (game_clock.js)
require('../bot/speedups').install() // cheaper equivalents of two library hot spots (speedups.js)
const path = require('path')
const net = require('net')

const log = (...args) => console.error(...args)
const channel = new net.Socket({ fd: settings.controlFd ?? 3, readable: true, writable: true })
const protocolOut = (line) => channel.write(line)

// Plugin files in load order: one concern each.
const PLUGINS = ['batching', 'guard', 'refusals', 'interact', 'player_list', 'teleport', 'movement', 'inventory', 'windows', 'blocks', 'crafting', 'furnace',
  'chest', 'drops', 'pickup', 'farming', 'crops', 'entities', 'mobs', 'attack_cooldown', 'player_health', 'reach', 'dig_time', 'placing', 'fill', 'no_commands', 'events', 'replay', 'watch', 'chunks', 'lockstep']

function main () {
  const mc = require('flying-squid')
  const plugins = Object.fromEntries(PLUGINS.map(name => [path.join(__dirname, 'plugins', name + '.js'), {}]))
  const serv = mc.createMCServer({
    port: settings.port ?? 25565,
    host: settings.host ?? '127.0.0.1',
    'online-mode': false,
    motd: 'PillagerBench arena',
    'max-players': settings.maxPlayers ?? 20,
    logging: false,
    gameMode: 0,
    difficulty: 0,
    'everybody-op': false,
    worldFolder: undefined,
    generation: { name: path.join(__dirname, 'world.js'), options: {} },
    kickTimeout: 3600 * 1000,
    plugins,
    'view-distance': settings.viewDistance ?? 4,
    'max-entities': settings.maxEntities ?? 1000,
    'player-list-text': { header: { text: 'PillagerBench' }, footer: { text: '' } },
    version: '1.16.5',
    // minecraft-protocol checks the type definitions of each login's plugin channels with ajv, compiled
    // afresh per login: about 0.2 s of the server's CPU each (profiles of a match's setup). The types are
    // the library's own; mineflayer turns the same check off on the bots' side.
    validateChannelProtocol: false,
    cropGrowthChance: settings.cropGrowthChance,
    idleLimitMs: settings.idleLimitMs // plugins/lockstep.js
  })
  serv.pb.tps = 20
  serv.pb.operators = settings.operators || []
  serv.on('error', (err) => {
    log('[server] error', err && err.stack ? err.stack : err)
    if (err && err.code === 'EADDRINUSE' && !serv.listeningPort) { // before `listening`: we cannot start
      const where = `${settings.host ?? '127.0.0.1'}:${settings.port}`
      protocolOut(JSON.stringify({ event: 'failed', error: `port ${where} is already in use (choose another with server.port=..., or 0 for a free port)` }) + '\n', () => process.exit(2))
    }
  })
  process.on('uncaughtException', (err) => log('[server] uncaught', err && err.stack ? err.stack : err))
  process.on('unhandledRejection', (err) => log('[server] unhandled rejection', err && err.stack ? err.stack : err))

  require('./control').attach(serv, { input: channel, write: protocolOut })
  serv.on('control_closed', () => shutdown(serv))
  process.on('SIGTERM', () => shutdown(serv))
  process.on('SIGINT', () => shutdown(serv))

  serv.once('listening', async (port) => {
    await serv.waitForReady?.(10000).catch(() => {})
    if (settings.tps && settings.tps !== 20) { serv.setTickInterval(settings.tps); serv.pb.tps = settings.tps }
    let watch = null
    if (settings.watch) { // the live view (plugins/watch.js): its port must be free, or the server does not start
      try {
        watch = await serv.pb.watch.start(settings.watch)
      } catch (err) {
        protocolOut(JSON.stringify({ event: 'failed', error: err.message }) + '\n', () => process.exit(2))
        return
      }
    }
    protocolOut(JSON.stringify({ event: 'ready', port, version: '1.16.5', watch }) + '\n')
  })
}

let stopping = false
function shutdown (serv) {
  if (stopping) return
  stopping = true
  for (const p of serv.players) { try { p.kick('Server stopping') } catch (_) {} }
  serv.pb.watch?.stop()
  Promise.race([serv.destroy?.(), new Promise(resolve => clock.real.setTimeout(resolve, 1000))])
    .finally(() => process.exit(0))
}

main()
