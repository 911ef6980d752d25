// A remote team in JavaScript (Node, no packages): the benchmark's remote-team protocol
// (docs/remote-teams.md). Both players harvest in Mushroom War; after 10 s of game the second
// player gets a new program that also talks.
//   node examples/remote_team.js 8801 &
//   pillagerbench run red=remote red.url=http://127.0.0.1:8801 blue=passive
'use strict'
const http = require('http')

const BLOCKS = { red: 'red_mushroom_block', blue: 'brown_mushroom_block' }
const harvest = (block) => `while (true) { await mineBlock(bot, '${block}', 4); await bot.waitForTicks(10) }`
let side = null
let switched = false

function reply (message, path) {
  if (path === '/pregame') {
    side = message.side
    switched = false
    const programs = {}
    for (const p of side.players) programs[p.name] = harvest(BLOCKS[side.key])
    return { programs }
  }
  if (path === '/events' && side && !switched && message.t >= 10) {
    switched = true
    const name = side.players[side.players.length - 1].name
    return { programs: { [name]: "bot.chat('new orders'); " + harvest(BLOCKS[side.key]) } }
  }
  return {}
}

const server = http.createServer((req, res) => {
  let body = ''
  req.on('data', (chunk) => { body += chunk })
  req.on('end', () => {
    const answer = req.method === 'GET' ? { protocol: 1, name: 'js-harvesters' } : reply(JSON.parse(body), req.url)
    res.writeHead(200, { 'Content-Type': 'application/json' })
    res.end(JSON.stringify(answer))
  })
})
server.listen(Number(process.argv[2] || 8801), '127.0.0.1', () => {
  console.log(`remote team on http://127.0.0.1:${server.address().port}`)
})
