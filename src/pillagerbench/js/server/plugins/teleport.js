'use strict'
// Teleports that stick.
// - Until the client confirms a teleport, its movement packets (sent from the old position) are
//   ignored; flying-squid applied them and snapped the player back.
// - the chunks around the destination are sent even when an earlier chunk send was under way;
// - flying-squid re-sends the login position once the client has loaded its chunks, which undid
//   a teleport made right after spawning; after a teleport that re-send keeps the current position.
module.exports.server = function (serv) {
  serv.pb.teleport = async (player, pos, yaw, pitch) => {
    player.pbTeleporting = Date.now()
    player.pbTeleported = true
    await player.sendPosition(pos, false, true) // moves the entity and tells the others
    player.position = pos
    player.updateAndSpawn() // who sees whom: flying-squid ran it before the position changed
    player._client.write('position', {
      x: pos.x, y: pos.y, z: pos.z,
      yaw: yaw ?? player.yaw * 360 / 256,
      pitch: pitch ?? player.pitch * 360 / 256,
      flags: 0,
      teleportId: 1
    })
    // flying-squid sends the chunks of a new place only if it is not busy sending others; make sure.
    for (let i = 0; i < 150 && player.sendingChunks; i++) await new Promise(resolve => setTimeout(resolve, 20))
    if (player.lastPositionChunkUpdated !== pos) await player.worldSendRestOfChunks()
  }
}

module.exports.player = function (player, serv) {
  player.pbTeleporting = 0
  player._client.on('teleport_confirm', () => { player.pbTeleporting = 0 })
  player.on('move_cancel', (data, cancel) => {
    if (!data.teleport && player.pbTeleporting && Date.now() - player.pbTeleporting < 3000) cancel(false)
  })
  setImmediate(() => {
    const sendSelfPosition = player.sendSelfPosition
    player.sendSelfPosition = (newPosition) => sendSelfPosition(player.pbTeleported ? undefined : newPosition)
  })
}
