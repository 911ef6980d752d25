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
const { judgeMove, newMoveState, airborneTooLong } = require('../limits')

module.exports.server = function (serv) {
  const reg = serv.registry
  // Height of the top of each block state's collision box (0: none; 1 for water, ladders … a player stands in).
  const tops = new Map()
  const shapes = reg.blockCollisionShapes
  const topOf = (stateId) => {
    let top = tops.get(stateId)
    if (top !== undefined) return top
    const b = reg.blocksByStateId[stateId]
    top = 0
    if (b && SUPPORTING.includes(b.name)) top = 1
    else if (b && shapes) {
      const ref = shapes.blocks[b.name]
      const list = Array.isArray(ref) ? shapes.shapes[ref[stateId - b.minStateId]] : shapes.shapes[ref]
      for (const box of list || []) top = Math.max(top, box[4])
    }
    tops.set(stateId, top)
    return top
  }
  const probe = new Vec3(0, 0, 0)
  // Height of what a player box with its feet at `pos` stands on (see limits.judgeMove), or null.
  serv.pb.standing = (world, pos) => {
    const half = 0.3
    let ground = null
    for (const dy of [0, -MOVEMENT.supportDepth]) {
      for (const [dx, dz] of [[-half, -half], [-half, half], [half, -half], [half, half]]) {
        probe.set(Math.floor(pos.x + dx), Math.floor(pos.y + dy - 1e-3), Math.floor(pos.z + dz))
        if (!world.sync.getColumnAt(probe)) return pos.y // an unloaded column is given the benefit of the doubt
        const top = topOf(world.sync.getBlockStateId(probe))
        if (top > 0 && pos.y - (probe.y + top) <= MOVEMENT.supportDepth) ground = Math.max(ground ?? -Infinity, Math.min(pos.y, probe.y + top))
      }
    }
    return ground
  }
  serv.on('tick', serv.guarded('airborne', () => { for (const p of serv.players) p.pbCheckAirborne?.() }))
  // The top of the ground below `pos` (the first block with a collision box), or pos itself.
  serv.pb.groundBelow = (world, pos) => {
    for (let y = Math.floor(pos.y); y >= 0; y--) {
      const top = topOf(world.sync.getBlockStateId(probe.set(Math.floor(pos.x), y, Math.floor(pos.z))))
      if (top > 0 && y + top <= pos.y + 1e-6) return new Vec3(pos.x, y + top, pos.z)
    }
    return pos
  }
}

module.exports.player = function (player, serv) {
  const checked = () => player.gameMode === 0 || player.gameMode === 2
  let state = null
  const reset = (pos) => { state = newMoveState(pos, Date.now()) }
  player.on('spawned', () => reset(player.position))
  const teleporting = () => player.pbTeleporting && Date.now() - player.pbTeleporting < 3000 // teleport.js ignores stale moves
  let keep = null // what a "put back" keeps from before: it does not make the air under the player ground
  player.on('move_cancel', serv.guarded('movement', (data, cancel) => {
    if (data.teleport || !state || !checked()) {
      reset(data.position)
      if (data.teleport && keep) { Object.assign(state, keep); keep = null }
      return
    }
    if (teleporting()) return
    const verdict = judgeMove(state, data.position, serv.pb.standing(player.world, data.position), Date.now())
    if (!verdict) return
    cancel(false)
    correct(verdict)
  }))
  // A hovering client sends the same position, which flying-squid drops before any check: look every tick.
  player.pbCheckAirborne = () => {
    if (!state || !checked() || teleporting()) return
    const verdict = airborneTooLong(state, Date.now())
    if (verdict) correct(verdict)
  }
  function correct (verdict) {
    const to = verdict.to === 'down' ? serv.pb.groundBelow(player.world, new Vec3(state.last.x, state.last.y, state.last.z)) : new Vec3(state.last.x, state.last.y, state.last.z)
    serv.pb.refuse(player, 'move', `${verdict.reason}: ${verdict.to === 'down' ? 'brought down' : 'put back'} to (${to.x.toFixed(1)}, ${to.y.toFixed(1)}, ${to.z.toFixed(1)})`)
    keep = verdict.to === 'back' ? { groundY: state.groundY, airSince: state.airSince, stallSince: state.stallSince } : null
    reset(to)
    if (keep) Object.assign(state, keep)
    serv.pb.teleport(player, to).catch(err => serv.emit('pluginError', err, 'movement correction'))
  }
}
