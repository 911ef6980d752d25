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
  if (elapsedMs >= t.minProgress * expectedMs - t.slackMs) return null
  return `broken too fast (${Math.round(elapsedMs)} ms of the ${Math.round(expectedMs)} ms it takes)`
}

// Attack strength (0..1) `ticks` game ticks after the last attack or change of held item, and the
// share of the damage a hit then does.
function attackStrength (ticks, heldName, t = ATTACK_SPEED) {
  const speed = t[heldName] ?? t.hand
  return Math.max(0, Math.min(1, (ticks + 0.5) / (20 / speed)))
}
const damageScale = (strength) => 0.2 + 0.8 * strength * strength

// Movement. `state` is the player's (see newMoveState): the last accepted position, the height it
// last stood on, since when it has been in the air and since when it has not been falling (ms), and
// its speed bucket. `ground` is the height of what the server sees the new position stand on (the
// top of a block's collision box within MOVEMENT.supportDepth below the feet, or the feet
// themselves in water or on a ladder), null when nothing.
// judgeMove returns null (the move is accepted and `state` advanced) or {reason, to: 'back' | 'down'}:
// put back to state.last, or brought down to the ground below.
function newMoveState (pos, now, t = MOVEMENT) {
  return { last: { x: pos.x, y: pos.y, z: pos.z }, groundY: pos.y, airSince: null, stallSince: null, budget: t.burst, at: now }
}

function judgeMove (state, pos, ground, now, t = MOVEMENT) {
  if (![pos.x, pos.y, pos.z].every(Number.isFinite)) return { reason: 'moved to an invalid position', to: 'back' }
  const supported = ground !== null && ground !== undefined
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
  const next = supported
    ? { airSince: null, stallSince: null, groundY: ground }
    : { airSince: state.airSince ?? now, stallSince: dy < -0.01 ? now : (state.stallSince ?? now), groundY: state.groundY }
  const stuck = airborneTooLong(next, now, t)
  if (stuck) return stuck
  Object.assign(state, next, { budget: budget - step, at: now, last: { x: pos.x, y: pos.y, z: pos.z } })
  return null
}

// A player in the air that has not fallen for MOVEMENT.hoverMs, or has been in the air for
// MOVEMENT.flyMs, is brought down (also checked every tick: a hovering client sends few packets).
function airborneTooLong (state, now, t = MOVEMENT) {
  if (state.stallSince !== null && now - state.stallSince > t.hoverMs) {
    return { reason: `hovered in the air for ${((now - state.stallSince) / 1000).toFixed(1)} s without falling`, to: 'down' }
  }
  if (state.airSince !== null && now - state.airSince > t.flyMs) {
    return { reason: `flew: ${((now - state.airSince) / 1000).toFixed(1)} s in the air`, to: 'down' }
  }
  return null
}

module.exports = { digTooFar, useTooFar, containerTooFar, entityTooFar, digTooFast, attackStrength, damageScale, newMoveState, judgeMove, airborneTooLong }
