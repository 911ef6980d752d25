'use strict'
// Dig time, as vanilla 1.16.5 checks it: a block is broken only if the time since the player
// started digging it is at least DIG.minProgress (0.7) of its dig time with the tool the server
// says it holds (prismarine-block's digTime: hardness, the tool's speed, on the ground, not in
// water). A finish that comes too early, or without a start, becomes a cancel: the block stays and
// the client is told so.
const { Vec3 } = require('vec3')
const { digTooFast } = require('../limits')

module.exports.server = function (serv) {
  serv.pb.gate('block_dig', (player, packet) => {
    if (player.gameMode !== 0 || !packet || (packet.status !== 0 && packet.status !== 2)) return null
    const pos = new Vec3(packet.location.x, packet.location.y, packet.location.z)
    const key = pos.toString()
    if (packet.status === 0) { player.pbDigStart = { key, at: Date.now() }; return null }
    const start = player.pbDigStart
    player.pbDigStart = null
    const block = player.world.sync.getBlock(pos)
    if (!block || block.type === 0) return null
    let reason = null
    if (!start || start.key !== key) reason = `finished digging ${block.name} at (${key.slice(1, -1)}) without starting it`
    else {
      const held = player.inventory.slots[36 + player.heldItemSlot]
      const expected = block.digTime(held ? held.type : null, false, false, false, [], {})
      const tooFast = digTooFast(Date.now() - start.at, expected)
      if (tooFast) reason = `${block.name} at (${key.slice(1, -1)}) ${tooFast}`
    }
    if (!reason) return null
    packet.status = 1 // flying-squid then cancels the dig (and stops its animation)
    serv.pb.resendBlock(player, pos)
    return { action: 'dig', reason, pass: true }
  })
}
