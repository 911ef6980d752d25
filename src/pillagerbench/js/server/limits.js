'use strict'
// The maths of fair play (vanilla 1.16.5's limits, numbers in tables.js), kept apart from the
// plugins so that it can be tested alone. Positions are {x, y, z}; a block position is its corner.
const { REACH, DIG, MOVEMENT, ATTACK_SPEED } = require('./tables')

const sq = (v) => v * v
const centreSq = (from, block, lift = 0) =>
  sq(from.x - (block.x + 0.5)) + sq(from.y + lift - (block.y + 0.5)) + sq(from.z - (block.z + 0.5))

// Each returns null when allowed, else the distance (blocks) that was too far.
function digTooFar (feet, block, t = REACH) {
  const d2 = centreSq(feet, block, t.digEyeHeight)
  return d2 > t.digSq ? Math.sqrt(d2) : null
}
function useTooFar (feet, block, t = REACH) {
  const d2 = centreSq(feet, block)
  return d2 >= t.useBlockSq ? Math.sqrt(d2) : null
}
function containerTooFar (feet, block, t = REACH) {
  const d2 = centreSq(feet, block)
  return d2 > t.containerSq ? Math.sqrt(d2) : null
}
function entityTooFar (feet, entity, t = REACH) {
  const d2 = sq(feet.x - entity.x) + sq(feet.y - entity.y) + sq(feet.z - entity.z)
  return d2 >= t.entitySq ? Math.sqrt(d2) : null
}

// Dig time: null when the block may break after `elapsedMs` of digging it, else the reason.
function digTooFast (elapsedMs, expectedMs, t = DIG) {
  if (elapsedMs >= t.minProgress * expectedMs) return null
  return `broken too fast (${Math.round(elapsedMs)} ms of the ${Math.round(expectedMs)} ms it takes)`
}

// Attack strength (0..1) `ticks` game ticks after the last attack or change of held item, and the
// share of the damage a hit then does.
function attackStrength (ticks, heldName, t = ATTACK_SPEED) {
  const speed = t[heldName] ?? t.hand
  return Math.max(0, Math.min(1, (ticks + 0.5) / (20 / speed)))
}
const damageScale = (strength) => 0.2 + 0.8 * strength * strength

// Movement. `state` is the player's: {last: {x,y,z}, groundY, air, stall, budget, at} (see
// newMoveState); `supported` says whether the server sees a block under the new position.
// Returns null (the move is accepted and `state` advanced) or {reason, to: 'back' | 'down'}:
// put back to state.last, or brought down to the ground below.
function newMoveState (pos, now, t = MOVEMENT) {
  return { last: { x: pos.x, y: pos.y, z: pos.z }, groundY: pos.y, air: 0, stall: 0, budget: t.burst, at: now }
}

function judgeMove (state, pos, supported, now, t = MOVEMENT) {
  if (![pos.x, pos.y, pos.z].every(Number.isFinite)) return { reason: 'moved to an invalid position', to: 'back' }
  const last = state.last
  const step = Math.hypot(pos.x - last.x, pos.z - last.z)
  const dy = pos.y - last.y
  const budget = Math.min(t.burst, state.budget + Math.max(0, now - state.at) / 1000 * t.speed)
  if (step > t.maxStep) return { reason: `moved too quickly (${step.toFixed(1)} blocks in one move; at most ${t.maxStep})`, to: 'back' }
  if (step > budget) return { reason: `moved too quickly (faster than ${t.speed} blocks/s)`, to: 'back' }
  if (dy > t.maxRise) return { reason: `moved up too quickly (${dy.toFixed(1)} blocks in one move; at most ${t.maxRise})`, to: 'back' }
  if (-dy > t.maxFall) return { reason: `moved down too quickly (${(-dy).toFixed(1)} blocks in one move; at most ${t.maxFall})`, to: 'back' }
  if (!supported && pos.y > state.groundY + t.jumpHeight) {
    return { reason: `rose ${(pos.y - state.groundY).toFixed(1)} blocks with nothing to stand on (a jump reaches 1.25)`, to: 'back' }
  }
  const air = supported ? 0 : state.air + 1
  const stall = supported ? 0 : state.stall + (dy > -0.01 ? 1 : 0)
  if (stall > t.hoverPackets) return { reason: `hovered in the air for ${stall} moves without falling`, to: 'down' }
  if (air > t.flyPackets) return { reason: `flew: ${air} moves in the air`, to: 'down' }
  state.budget = budget - step
  state.at = now
  state.last = { x: pos.x, y: pos.y, z: pos.z }
  state.air = air
  state.stall = stall
  if (supported) state.groundY = pos.y
  return null
}

module.exports = { digTooFar, useTooFar, containerTooFar, entityTooFar, digTooFast, attackStrength, damageScale, newMoveState, judgeMove }
