'use strict'
// Block drops by our rules (tables.BLOCK_DROPS): chance and count ranges, crop age. Blocks without a
// rule drop their loot-table items once, as flying-squid does. Reports every dug block.
const { Vec3 } = require('vec3')
const { BLOCK_DROPS, GROWTH, PICKUP } = require('../tables')
const { rollCount } = require('../util')
const { seededRandom, seedOf } = require('../../clock/random')

module.exports.server = function (serv) {
  const reg = serv.registry
  serv.pb.rollCount = (range) => rollCount(range, serv.pb.random)
  serv.pb.random = Math.random
  serv.pb.seedRandom = (seed) => { // every draw of the server's, flying-squid's too (js/clock/random.js)
    serv.pb.seed = seed
    serv.pb.random = seededRandom(seed)
    Math.random = seededRandom(seedOf(seed, 'server'))
  }
  // On the lockstep clock, the draws of each tick of a game come from that tick's own seed: a draw made
  // at a moment the game does not decide (a connection's keep-alive, on a timer begun at its login)
  // then cannot shift the draws of every later tick (js/server/plugins/lockstep.js).
  serv.pb.reseed = (tick) => {
    if (serv.pb.seed === undefined) return
    serv.pb.random = seededRandom(seedOf(serv.pb.seed, `tick ${tick}`))
    Math.random = seededRandom(seedOf(serv.pb.seed, `server tick ${tick}`))
  }

  // [{id, count}] for a dug block (properties decide ripeness).
  serv.pb.dropsFor = (block) => {
    let rule = BLOCK_DROPS[block.name]
    if (rule && !Array.isArray(rule)) {
      const g = GROWTH[block.name]
      const age = Number((block.getProperties?.() || {})[g.prop] ?? 0)
      rule = rule.byAge ? (rule.byAge[age] || rule.young) : age >= g.max ? rule.ripe : rule.young
    }
    if (!rule) return null
    return rule.filter(d => d.chance === undefined || serv.pb.random() < d.chance)
      .map(d => ({ id: reg.itemsByName[d.item].id, count: serv.pb.rollCount(d.count) + bonus(d.bonus) })).filter(d => d.count > 0)
  }
  // binomial_with_bonus_count: one more for each of n trials that succeeds with p
  const bonus = (b) => {
    let n = 0
    if (b) for (let i = 0; i < b[0]; i++) if (serv.pb.random() < b[1]) n++
    return n
  }

  // cause: 'block' (dug, harvested) or 'mob' (loot), for the pickup delay (tables.PICKUP)
  serv.pb.spawnDrops = (world, position, drops, cause = 'block') => {
    for (const d of drops) {
      serv.spawnObject(reg.entitiesByName.item.id, world, position.offset(0.5, 0.5, 0.5), {
        velocity: new Vec3(Math.random() * 2 - 1, 2, Math.random() * 2 - 1),
        itemId: d.id, itemCount: d.count, pickupDelayTicks: PICKUP.delayTicks[cause], deathTime: 300000
      })
    }
  }
}

module.exports.player = function (player, serv) {
  player.on('dug_cancel', serv.guarded('dug rules', (data) => {
    const ours = serv.pb.dropsFor(data.block)
    const base = data.drops[0]
    if (ours && base) {
      const template = { ...base }
      data.drops.length = 0
      for (const d of ours) data.drops.push({ ...template, blockDropId: d.id, blockDropCount: d.count })
    } else if (ours) {
      data.drops.length = 0
    }
    for (const d of data.drops) d.blockDropCount = d.blockDropCount || 1
  }))
  player.on('dug', serv.guarded('dug event', (data, cancelled) => {
    if (cancelled) return
    const p = data.position
    serv.emit('control_event', {
      event: 'block_dug', player: player.username, pos: [p.x, p.y, p.z], block: data.block.name,
      properties: data.block.getProperties?.() || {},
      drops: data.drops.map(d => [serv.registry.items[d.blockDropId]?.name, d.blockDropCount || 1])
    })
  }))
}
