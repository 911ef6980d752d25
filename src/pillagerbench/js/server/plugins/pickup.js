'use strict'
// Item pickup as in vanilla 1.16, replacing flying-squid's (which gave every item past its delay
// to players[0] of those within a 1.75-block sphere: whoever joined first, i.e. always one side).
// - reach: the player's box grown by PICKUP.reach touches the item's box (see ../pickup.js);
// - delay: counted in game ticks from the spawn, by cause (PICKUP.delayTicks: block, mob, toss);
//   callers of serv.spawnObject pass `pickupDelayTicks`, or flying-squid's `pickupTime` in ms;
// - order: every tick the players are visited in a fresh random order (the server's seeded random
//   source), each taking every ready item it touches, as vanilla's per-player loop does. Vanilla
//   visits players in connection order; a benchmark must not let the join order (the team order)
//   decide who gets a contested item, and a per-tick draw keeps it fair within every episode.
const { touches, shuffled } = require('../pickup')

module.exports.server = function (serv) {
  serv.once('asap', () => {
    const spawnObject = serv.spawnObject
    serv.spawnObject = (type, world, position, options = {}) => {
      const entity = spawnObject(type, world, position, options)
      if (entity.itemId) {
        entity.pbPickupDelay = options.pickupDelayTicks ?? Math.round((options.pickupTime ?? 0) / 50)
        entity.pickupTime = undefined // flying-squid's own pickup never sees it
      }
      return entity
    }
  })

  serv.on('tick', serv.guarded('pickup', () => {
    const items = []
    for (const entity of Object.values(serv.entities)) {
      if (entity.pbPickupDelay === undefined || entity.collected) continue
      if (entity.pbPickupDelay > 0) entity.pbPickupDelay--
      else items.push(entity)
    }
    if (!items.length) return
    const players = serv.players.filter(p => !(p.health <= 0) && p.gameMode !== 3)
    for (const player of shuffled(players, serv.pb.random)) {
      for (const item of items) {
        if (!item.collected && item.world === player.world && touches(player.position, item.position)) player.collect(item)
      }
    }
  }))
}
