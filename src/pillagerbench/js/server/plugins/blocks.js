'use strict'
// Block edits for the game master and arena builder: set without neighbour updates, read with
// properties. Growable blocks that get set are tracked for crop growth. A block already in the
// state asked for is neither rewritten nor sent: resetting an arena fills its whole box, mostly
// with what is already there (air), and sending those no-op changes to every player was
// 12,000 packets per player per Dash & Dine reset (docs/performance.md).
const { GROWTH } = require('../tables')

module.exports.server = function (serv) {
  serv.pb.setBlockQuiet = async (pos, stateId) => {
    const world = serv.overworld
    if (await world.getBlockStateId(pos) !== stateId) {
      for (const p of serv.players) if (p.world === world) p.sendBlock(pos, stateId)
      await world.setBlockStateId(pos, stateId)
    }
    const name = serv.registry.blocksByStateId[stateId]?.name
    if (GROWTH[name]) serv.pb.crops.track(pos)
  }
  serv.pb.describeBlock = async (pos) => {
    const b = await serv.overworld.getBlock(pos)
    return { name: b.name, properties: b.getProperties ? b.getProperties() : {}, state: b.stateId }
  }
}
