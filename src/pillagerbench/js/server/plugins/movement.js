'use strict'
// Movement, checked on every position the client sends (tables.MOVEMENT, maths in ../limits.js):
// a move that is too long for one packet, too fast on average, rises too quickly or higher than a
// jump with nothing to stand on is refused and the player is put back where it was; a player that
// hovers or flies (off the ground too long without falling) is brought down onto the ground below
// it. Both are position corrections (a teleport the client must confirm, as vanilla's), and the
// client's moves sent before it confirmed are ignored (teleport.js). "Standing" is the server's own
// look at the blocks under the player's box, not the client's onGround flag.
// Only survival and adventure players are checked; a teleport by the server starts afresh.
const { Vec3 } = require('vec3')
const { MOVEMENT, SUPPORTING } = require('../tables')
const { judgeMove, newMoveState } = require('../limits')

module.exports.server = function (serv) {
  const reg = serv.registry
  const supportIds = new Set()
  for (const b of reg.blocksArray) {
    if (b.boundingBox === 'block' || SUPPORTING.includes(b.name)) supportIds.add(b.id)
  }
  const probe = new Vec3(0, 0, 0)
  const solidAt = (world, x, y, z) => {
    probe.set(Math.floor(x), Math.floor(y), Math.floor(z))
    if (!world.sync.getColumnAt(probe)) return true // an unloaded column is given the benefit of the doubt
    return supportIds.has(world.sync.getBlockType(probe))
  }
  // A block under (or at) the feet of a player box at `pos`, within MOVEMENT.supportDepth below them.
  serv.pb.standing = (world, pos) => {
    const half = 0.3
    for (const dy of [0, -MOVEMENT.supportDepth]) {
      for (const [dx, dz] of [[-half, -half], [-half, half], [half, -half], [half, half]]) {
        if (solidAt(world, pos.x + dx, pos.y + dy - 1e-3, pos.z + dz)) return true
      }
    }
    return false
  }
  // The top of the ground below `pos` (the first block with a collision box), or pos itself.
  serv.pb.groundBelow = (world, pos) => {
    for (let y = Math.floor(pos.y); y >= 0; y--) {
      if (solidAt(world, pos.x, y, pos.z)) return new Vec3(pos.x, y + 1, pos.z)
    }
    return pos
  }
}

module.exports.player = function (player, serv) {
  const checked = () => player.gameMode === 0 || player.gameMode === 2
  let state = null
  const reset = (pos) => { state = newMoveState(pos, Date.now()) }
  player.on('spawned', () => reset(player.position))
  player.on('move_cancel', serv.guarded('movement', (data, cancel) => {
    if (data.teleport || !state || !checked()) return reset(data.position)
    if (player.pbTeleporting && Date.now() - player.pbTeleporting < 3000) return // stale: teleport.js ignores it
    const verdict = judgeMove(state, data.position, serv.pb.standing(player.world, data.position), Date.now())
    if (!verdict) return
    cancel(false)
    const to = verdict.to === 'down' ? serv.pb.groundBelow(player.world, new Vec3(state.last.x, state.last.y, state.last.z)) : new Vec3(state.last.x, state.last.y, state.last.z)
    serv.pb.refuse(player, 'move', `${verdict.reason}: ${verdict.to === 'down' ? 'brought down' : 'put back'} to (${to.x.toFixed(1)}, ${to.y.toFixed(1)}, ${to.z.toFixed(1)})`)
    reset(to)
    serv.pb.teleport(player, to).catch(err => serv.emit('pluginError', err, 'movement correction'))
  }))
}
