'use strict'
// Which chunks each player has, for a lockstep game to begin the same way every time
// (js/server/plugins/lockstep.js, startGame). flying-squid sends the chunks around a player a few per
// tick after a teleport or a long move, and unloads only those more than the view distance away, so
// the chunks a bot had when a game began depended on where it had been and on how many ticks the reset
// took on the wall clock: a bot short of a chunk, or with one more, searched its paths differently.
// - `serv.pb.squareChunks()`: once no chunks are being sent to anyone, each player gets exactly the
//   square flying-squid sends around where it stands (those missing sent, the others unloaded, on the
//   server and in the bot).
module.exports.server = function (serv, settings) {
  const sends = { pending: 0, waiters: [] }
  serv.pb.chunkSends = sends
  const noneUnderWay = () => new Promise(resolve => {
    if (sends.pending === 0) resolve()
    else sends.waiters.push(resolve)
  })
  serv.pb.squareChunks = async () => {
    await noneUnderWay()
    for (const player of serv.players) {
      if (!player.loadedChunks || !player.position || !player.worldSendRestOfChunks) continue
      await player.worldSendRestOfChunks() // the square around where it stands (as flying-squid's own)
      const view = Math.min(player.view ?? Infinity, settings['view-distance'])
      const [cx, cz] = [Math.floor(player.position.x / 16), Math.floor(player.position.z / 16)]
      const inside = (x, z) => x >= cx - view && x < cx + view && z >= cz - view && z < cz + view
      for (const key of Object.keys(player.loadedChunks)) {
        const [x, z] = key.split(',').map(Number)
        if (!inside(x, z)) player._unloadChunk(x, z)
      }
    }
  }
}

// Count the chunk sends under way (flying-squid's worldSendRestOfChunks, however it is called).
module.exports.player = function (player, serv) {
  const send = player.worldSendRestOfChunks
  const sends = serv.pb.chunkSends
  player.worldSendRestOfChunks = async (...args) => {
    sends.pending++
    try {
      return await send(...args)
    } finally {
      if (--sends.pending === 0) for (const resolve of sends.waiters.splice(0)) resolve()
    }
  }
}
