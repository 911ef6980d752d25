'use strict'
// Block edits for the game master and arena builder: set without neighbour updates, read with
// properties. Growable blocks that get set are tracked for crop growth.
const { GROWTH } = require('../tables')

module.exports.server = function (serv) {
  serv.pb.setBlockQuiet = async (pos, stateId) => {
    const world = serv.overworld
    for (const p of serv.players) if (p.world === world) p.sendBlock(pos, stateId)
    await world.setBlockStateId(pos, stateId)
    const name = serv.registry.blocksByStateId[stateId]?.name
    if (GROWTH[name]) serv.pb.crops.track(pos)
  }
  serv.pb.describeBlock = async (pos) => {
    const b = await serv.overworld.getBlock(pos)
    return { name: b.name, properties: b.getProperties ? b.getProperties() : {}, state: b.stateId }
  }
}
