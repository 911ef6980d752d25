'use strict'
// A destroyed entity (a killed mob, a picked-up item) disappears for every player in its world.
// flying-squid told only the players that were near it when it spawned, so players who came
// later kept seeing killed mobs forever.
// And nothing of it is sent after: flying-squid's entity tick computes an item's physics with an
// await and then sends its move, so an item picked up meanwhile (plugins/pickup.js, the same tick)
// had its `rel_entity_move` sent after its `entity_destroy`. mineflayer makes an entity of any id a
// packet names: every bot near it kept one more nameless entity at each such pickup, for the whole
// series (about 30 per 120-s Mushroom War episode, each looked at by every path search's collision
// index; benchmarks/day_of_play.py, docs/performance.md).
module.exports.server = function (serv) {
  serv.once('asap', () => {
    serv.destroyEntity = (entity) => {
      entity.sendPosition = () => Promise.resolve()
      for (const p of serv.players) {
        if (p.world === entity.world) p._client.write('entity_destroy', { entityIds: [entity.id] })
        if (p.nearbyEntities) p.nearbyEntities = p.nearbyEntities.filter(e => e !== entity)
      }
      delete serv.entities[entity.id]
    }
  })
}
