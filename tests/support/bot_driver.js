'use strict'
// Test-only: one real mineflayer bot that evaluates snippets sent as JSON lines on stdin
// ({id, code}) with `bot`, `mcData`, `Vec3`, `goals`, `Movements`, `sleep` in scope, and answers
// {id, ok, result|error} on stdout. Not sandboxed: tests use it to act like a (possibly malicious)
// client and then check the server's own state through the control channel.
const readline = require('readline')
const mineflayer = require('mineflayer')
const { pathfinder, Movements, goals } = require('mineflayer-pathfinder')
const { Vec3 } = require('vec3')

const opts = JSON.parse(process.argv[2])
const bot = mineflayer.createBot({ host: opts.host, port: opts.port, username: opts.username, version: '1.16.5', auth: 'offline', checkTimeoutInterval: 3600000 })
bot.loadPlugin(pathfinder)
const out = (o) => process.stdout.write(JSON.stringify(o) + '\n')
const sleep = (ms) => new Promise(resolve => setTimeout(resolve, ms))
const AsyncFunction = Object.getPrototypeOf(async function () {}).constructor

bot.once('spawn', () => {
  const mcData = require('minecraft-data')(bot.version)
  const moves = new Movements(bot)
  moves.canDig = false
  moves.allow1by1towers = false
  bot.pathfinder.setMovements(moves)
  out({ event: 'spawned' })
  const rl = readline.createInterface({ input: process.stdin })
  rl.on('line', async (line) => {
    const { id, code } = JSON.parse(line)
    try {
      const fn = new AsyncFunction('bot', 'mcData', 'Vec3', 'goals', 'Movements', 'sleep', code)
      const result = await fn(bot, mcData, Vec3, goals, Movements, sleep)
      out({ id, ok: true, result: result === undefined ? null : result })
    } catch (err) {
      out({ id, ok: false, error: String(err && err.stack ? err.stack : err) })
    }
  })
  rl.on('close', () => { bot.quit(); setTimeout(() => process.exit(0), 200) })
})
process.on('unhandledRejection', (err) => out({ event: 'unhandled', error: String(err) }))
bot.on('kicked', (reason) => { out({ event: 'kicked', reason: String(reason) }); process.exit(3) })
bot.on('error', (err) => out({ event: 'error', error: String(err) }))
bot.on('end', (reason) => { out({ event: 'end', reason: String(reason) }); process.exit(0) })
