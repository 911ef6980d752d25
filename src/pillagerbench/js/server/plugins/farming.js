'use strict'
// Farming: hoe tilling, planting seeds and other crops, sweet berry harvest by right-click.
const { PLANTING, TILLABLE, HOES } = require('../tables')
const { stateIdOf } = require('../util')

const FACE_TO_FACING = { 2: 'south', 3: 'north', 4: 'east', 5: 'west' } // cocoa faces its log

module.exports.server = function (serv) {
  const reg = serv.registry
  const heldName = (player) => player.inventory.slots[36 + player.heldItemSlot]?.name

  for (const soil of TILLABLE) {
    serv.pb.onBlockInteraction(soil, async ({ block, player }) => {
      if (!HOES.includes(heldName(player))) return false
      const above = await player.world.getBlock(block.position.offset(0, 1, 0))
      if (above.name !== 'air') return false
      await serv.setBlock(player.world, block.position, reg.blocksByName.farmland.defaultState)
      serv.emit('control_event', { event: 'block_tilled', player: player.username, pos: [block.position.x, block.position.y, block.position.z] })
      return true
    })
  }

  serv.pb.onBlockInteraction('sweet_berry_bush', async ({ block, player }) => {
    const age = Number(block.getProperties().age)
    if (age < 2) return true
    const drops = serv.pb.dropsFor(block)
    await serv.setBlock(player.world, block.position, stateIdOf(reg, 'sweet_berry_bush', { age: 1 }))
    serv.pb.spawnDrops(player.world, block.position, drops)
    serv.emit('control_event', { event: 'berries_harvested', player: player.username, pos: [block.position.x, block.position.y, block.position.z], count: drops.reduce((a, d) => a + d.count, 0) })
    return true
  })

  const none = { id: -1, data: 0 }
  const WATER_SIDES = [[1, 0], [-1, 0], [0, 1], [0, -1]]
  async function besideWater (world, pos) {
    for (const [dx, dz] of WATER_SIDES) {
      const name = (await world.getBlock(pos.offset(dx, 0, dz))).name
      if (name === 'water' || name === 'frosted_ice') return true
    }
    return false
  }
  serv.once('asap', () => { for (const [itemName, rule] of Object.entries(PLANTING)) registerPlanting(itemName, rule) })
  function registerPlanting (itemName, rule) {
    const block = reg.blocksByName[rule.block]
    serv.onItemPlace(itemName, serv.guarded(`plant ${itemName}`, async ({ player, placedPosition, referencePosition, direction }) => {
      const at = await player.world.getBlock(placedPosition)
      if (at.name !== 'air') return none
      let props = {}
      if (rule.side) {
        const ref = await player.world.getBlock(referencePosition)
        if (!rule.side.includes(ref.name) || !FACE_TO_FACING[direction]) return none
        props = { facing: FACE_TO_FACING[direction], age: 0 }
      } else {
        const below = await player.world.getBlock(placedPosition.offset(0, -1, 0))
        if (!rule.soil.includes(below.name)) return none
        if (rule.water?.includes(below.name) && !await besideWater(player.world, below.position)) return none
        if (block.states?.some(s => s.name === 'age')) props = { age: 0 }
      }
      serv.pb.crops.track(placedPosition)
      serv.emit('control_event', { event: 'planted', player: player.username, block: rule.block, pos: [placedPosition.x, placedPosition.y, placedPosition.z] })
      return { id: block.id, data: stateIdOf(reg, rule.block, props) - block.minStateId }
    }), false)
  }
}
