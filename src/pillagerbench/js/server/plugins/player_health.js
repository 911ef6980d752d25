'use strict'
// Player health as vanilla's on peaceful difficulty (tables.HEALTH): natural regeneration, immunity
// right after a hit (two attackers on one player do not double the damage), and thorny blocks (sweet
// berry bushes) that hurt a player moving through them. flying-squid had none of these: a hurt player
// stayed hurt for the rest of the episode. Only survival and adventure players are hurt, as vanilla's
// creative and spectator players are invulnerable.
const { HEALTH } = require('../tables')

module.exports.server = function (serv) {
  const reg = serv.registry
  const thornyIds = new Map() // block id -> rule
  for (const [name, rule] of Object.entries(HEALTH.thorny)) thornyIds.set(reg.blocksByName[name].id, rule)
  const ageOf = (stateId) => {
    const b = reg.blocksByStateId[stateId]
    return stateId - b.minStateId // the bush's only property is its age (0-3)
  }
  const vulnerable = (p) => (p.gameMode === 0 || p.gameMode === 2) && p.health > 0

  // The thorny block the player's box (deflated as vanilla's checkInsideBlocks) overlaps, if any.
  const EPS = 1e-7
  const half = 0.3
  const height = 1.8
  function thornIn (player) {
    const pos = player.position
    for (let x = Math.floor(pos.x - half + EPS); x <= Math.floor(pos.x + half - EPS); x++) {
      for (let y = Math.floor(pos.y + EPS); y <= Math.floor(pos.y + height - EPS); y++) {
        for (let z = Math.floor(pos.z - half + EPS); z <= Math.floor(pos.z + half - EPS); z++) {
          const p = { x, y, z }
          if (!player.world.sync.getColumnAt(p)) continue
          const stateId = player.world.sync.getBlockStateId(p)
          const rule = thornyIds.get(reg.blocksByStateId[stateId]?.id)
          if (rule && ageOf(stateId) > rule.minAge) return rule
        }
      }
    }
    return null
  }

  serv.on('tick', serv.guarded('player health', (delta, tick) => {
    for (const player of serv.players) {
      const last = player.pbLastTickPos
      player.pbLastTickPos = player.position.clone()
      if (!vulnerable(player)) continue
      if ((tick - (serv.pb.tick0 || 0)) % HEALTH.regeneration.everyTicks === 0 && player.health < HEALTH.max) { // from a game's start
        player.updateHealth(Math.min(HEALTH.max, player.health + HEALTH.regeneration.amount))
      }
      if (!last) continue
      const rule = thornIn(player)
      if (rule && (Math.abs(player.position.x - last.x) >= rule.minMove || Math.abs(player.position.z - last.z) >= rule.minMove)) {
        player.takeDamage({ damage: rule.damage })
      }
    }
  }))
}

module.exports.player = function (player, serv) {
  // Hurt immunity (LivingEntity.hurt): within immuneTicks of a full hit, a hit does only what it exceeds
  // that hit by, and nothing if it is not larger. Damage of a full health bar or more (kill) is not reduced.
  let hurtTick = -Infinity
  let lastHurt = 0
  player.once('spawned', () => {
    const takeDamage = player.takeDamage
    if (typeof takeDamage !== 'function') return
    player.takeDamage = (opts = {}) => {
      if (!(player.gameMode === 0 || player.gameMode === 2)) return
      const amount = opts.damage ?? 1
      let dealt = amount
      if (amount < HEALTH.max && serv.tickCount - hurtTick < HEALTH.immuneTicks) {
        if (amount <= lastHurt) return
        dealt = amount - lastHurt
        lastHurt = amount
      } else {
        lastHurt = amount
        hurtTick = serv.tickCount
      }
      return takeDamage({ ...opts, damage: dealt })
    }
  })
}
