'use strict'
// Our flat world generator: bedrock at y=0, dirt at y=1..2, grass_block on top at y=3
// (upstream's 1.19.4 layers shifted by +64, see DESIGN §1). Players stand at y=4.
const LAYERS = [['bedrock', 0], ['dirt', 1], ['dirt', 2], ['grass_block', 3]]
const GROUND_Y = 3

module.exports = function flatGenerator (options) {
  const { registry } = options
  const Chunk = require('prismarine-chunk')(registry)
  const { Vec3 } = require('vec3')
  const layers = LAYERS.map(([name, y]) => [registry.blocksByName[name].defaultState, y])
  const plains = registry.biomesByName.plains.id
  return function generateChunk () {
    const chunk = new Chunk()
    const p = new Vec3(0, 0, 0)
    for (p.x = 0; p.x < 16; p.x++) {
      for (p.z = 0; p.z < 16; p.z++) {
        for (const [stateId, y] of layers) { p.y = y; chunk.setBlockStateId(p, stateId) }
        for (p.y = 0; p.y < 256; p.y++) { chunk.setSkyLight(p, 15); chunk.setBiome(p, plains) }
      }
    }
    return chunk
  }
}
module.exports.GROUND_Y = GROUND_Y
