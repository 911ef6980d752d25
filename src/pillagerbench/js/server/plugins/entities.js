'use strict'
// A destroyed entity (a killed mob, a picked-up item) disappears for every player in its world.
// flying-squid told only the players that were near it when it spawned, so players who came
// later kept seeing killed mobs forever.
module.exports.server = function (serv) {
  serv.once('asap', () => {
    serv.destroyEntity = (entity) => {
      for (const p of serv.players) {
        if (p.world === entity.world) p._client.write('entity_destroy', { entityIds: [entity.id] })
        if (p.nearbyEntities) p.nearbyEntities = p.nearbyEntities.filter(e => e !== entity)
      }
      delete serv.entities[entity.id]
    }
  })
}
