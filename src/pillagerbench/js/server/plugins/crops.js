'use strict'
// Crop growth: every second each tracked crop advances one age step with probability
// `cropGrowthChance`; ripe melon/pumpkin stems grow fruit onto a free neighbouring soil block;
// sugar cane grows up to 3 high. Positions are tracked when planted or set by the control channel.
const { Vec3 } = require('vec3')
const { GROWTH, FRUIT_SOIL } = require('../tables')
const { stateIdOf } = require('../util')

const SIDES = [[1, 0, 'east'], [-1, 0, 'west'], [0, 1, 'south'], [0, -1, 'north']]

module.exports.server = function (serv, settings) {
  const reg = serv.registry
  const tracked = new Map() // "x,y,z" -> Vec3
  serv.pb.cropGrowthChance = settings.cropGrowthChance ?? 0.2
  serv.pb.crops = {
    track: (p) => tracked.set(`${p.x},${p.y},${p.z}`, new Vec3(p.x, p.y, p.z)),
    reset: () => tracked.clear(),
    count: () => tracked.size
  }

  async function grow (pos) {
    const world = serv.overworld
    const block = await world.getBlock(pos)
    const g = GROWTH[block.name]
    if (!g) { tracked.delete(`${pos.x},${pos.y},${pos.z}`); return }
    if (serv.pb.random() >= serv.pb.cropGrowthChance) return
    const props = block.getProperties()
    const age = Number(props[g.prop])
    if (age < g.max) return serv.setBlock(world, pos, stateIdOf(reg, block.name, { ...props, [g.prop]: age + 1 }))
    if (g.fruit) return growFruit(world, pos, g)
    if (g.column) return growColumn(world, pos, block, g)
  }

  async function growFruit (world, pos, g) {
    const [dx, dz, facing] = SIDES[Math.floor(serv.pb.random() * SIDES.length)]
    const target = pos.offset(dx, 0, dz)
    if ((await world.getBlock(target)).name !== 'air') return
    if (!FRUIT_SOIL.includes((await world.getBlock(target.offset(0, -1, 0))).name)) return
    await serv.setBlock(world, target, reg.blocksByName[g.fruit].defaultState)
    await serv.setBlock(world, pos, stateIdOf(reg, g.attached, { facing }))
  }

  async function growColumn (world, pos, block, g) {
    let height = 1
    while (height < g.column && (await world.getBlock(pos.offset(0, -height, 0))).name === block.name) height++
    const above = pos.offset(0, 1, 0)
    if (height >= g.column || (await world.getBlock(above)).name !== 'air') return
    await serv.setBlock(world, above, reg.blocksByName[block.name].defaultState)
    await serv.setBlock(world, pos, stateIdOf(reg, block.name, { age: 0 }))
    serv.pb.crops.track(above)
  }

  let busy = false
  serv.on('tick', (delta, tickCount) => {
    if (tickCount % 20 !== 0 || busy || tracked.size === 0) return
    busy = true
    Promise.all([...tracked.values()].map(p => grow(p).catch(err => serv.emit('pluginError', err, 'crop growth'))))
      .finally(() => { busy = false })
  })
}
