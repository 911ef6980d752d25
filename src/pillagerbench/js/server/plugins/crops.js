'use strict'
// Crop growth by vanilla random ticks (tables.GROWTH says how each crop grows). Every second each
// tracked crop gets the random ticks vanilla would have given it in those 20 game ticks (each tick
// randomTickSpeed / 4096 per block) and, for each, grows one step with its chance. Ripe melon and
// pumpkin stems grow fruit onto a free neighbouring soil block; a stem whose fruit is gone is a ripe
// stem again at once; sugar cane grows up to 3 high. Positions are tracked when planted or set by
// the control channel.
//
// `cropGrowthChance` > 0 replaces the vanilla rule by a fixed chance per crop per second (tests that
// want a crop to grow now).
const { Vec3 } = require('vec3')
const { GROWTH, FRUIT_SOIL, SECTION_BLOCKS } = require('../tables')
const { stateIdOf } = require('../util')
const clock = require('../../clock/game_clock')

const SIDES = [[1, 0, 'east'], [-1, 0, 'west'], [0, 1, 'south'], [0, -1, 'north']]
const FACING = { east: [1, 0], west: [-1, 0], south: [0, 1], north: [0, -1] }
const DIAGONALS = [[1, 1], [1, -1], [-1, 1], [-1, -1]]

module.exports.server = function (serv, settings) {
  const tracked = new Map() // "x,y,z" -> Vec3
  serv.pb.cropGrowthChance = settings.cropGrowthChance ?? 0
  serv.pb.randomTickSpeed = settings.randomTickSpeed ?? 0
  serv.pb.crops = {
    track: (p) => tracked.set(`${p.x},${p.y},${p.z}`, new Vec3(p.x, p.y, p.z)),
    reset: () => tracked.clear(),
    count: () => tracked.size,
    growthSpeed: (pos) => growthSpeed(serv, serv.overworld, pos)
  }

  serv.on('control_event', (e) => {
    if (e.event !== 'block_dug') return
    popUnsupported(serv, serv.overworld, new Vec3(...e.pos)).catch(err => serv.emit('pluginError', err, 'unsupported plants'))
    // a fruit broken next to its stem: the stem lets go at once (vanilla's neighbour update)
    if (e.block !== 'melon' && e.block !== 'pumpkin') return
    const p = new Vec3(...e.pos)
    for (const [dx, dz] of Object.values(FACING)) {
      const at = p.offset(dx, 0, dz)
      if (!tracked.has(`${at.x},${at.y},${at.z}`)) continue
      serv.overworld.getBlock(at).then(b => GROWTH[b.name]?.attachedTo && detach(serv, serv.overworld, at, b, GROWTH[b.name]))
        .catch(err => serv.emit('pluginError', err, 'stem update'))
    }
  })

  // On the lockstep clock crops grow during games only. Between games the clock keeps real time's pace,
  // so growth from the arena's build to the game's start came in as many steps as the reset took on the
  // wall clock, and a game of one seed began with its crops at different ages (docs/clock.md). The real
  // clock keeps its growth between games, as its reference figures were measured.
  const growingNow = () => !clock.lockstep || serv.pb.clock?.inGame() === true
  let busy = false
  serv.on('tick', (delta, tickCount) => {
    if ((tickCount - (serv.pb.tick0 || 0)) % 20 !== 0 || busy || tracked.size === 0) return // from a game's start (plugins/lockstep.js)
    if (!growingNow()) return
    busy = true
    Promise.all([...tracked.values()].map(p => grow(serv, tracked, p).catch(err => serv.emit('pluginError', err, 'crop growth'))))
      .finally(() => { busy = false })
  })
}

async function nameAt (serv, world, pos) {
  const sid = await world.getBlockStateId(pos)
  return { name: serv.registry.blocksByStateId[sid]?.name, sid }
}

// CropBlock.getGrowthSpeed: 1, plus the farmland under and around the crop (3 if moist, 1 if dry,
// a quarter of that for the 8 around), halved when the same crop grows beside it on two axes (or
// diagonally), as in rows of a field.
async function growthSpeed (serv, world, pos) {
  const farmland = serv.registry.blocksByName.farmland
  let f = 1
  for (let dx = -1; dx <= 1; dx++) {
    for (let dz = -1; dz <= 1; dz++) {
      const { name, sid } = await nameAt(serv, world, pos.offset(dx, -1, dz))
      let g = 0
      if (name === 'farmland') g = sid > farmland.minStateId ? 3 : 1 // moisture 0 is the first state
      if (dx !== 0 || dz !== 0) g /= 4
      f += g
    }
  }
  const self = (await nameAt(serv, world, pos)).name
  const same = async (dx, dz) => (await nameAt(serv, world, pos.offset(dx, 0, dz))).name === self
  const eastWest = await same(1, 0) || await same(-1, 0)
  const northSouth = await same(0, 1) || await same(0, -1)
  if (eastWest && northSouth) return f / 2
  for (const [dx, dz] of DIAGONALS) if (await same(dx, dz)) return f / 2
  return f
}

// Random ticks a block gets in 20 game ticks.
function randomTicks (serv) {
  const p = Math.min(1, serv.pb.randomTickSpeed / SECTION_BLOCKS)
  if (p <= 0) return 0
  let k = 0
  for (let i = 0; i < 20; i++) if (serv.pb.random() < p) k++
  return k
}

async function chanceOf (serv, world, pos, g) {
  if (typeof g.chance === 'number') return g.chance
  const crop = 1 / (Math.floor(25 / await growthSpeed(serv, world, pos)) + 1)
  return g.chance === 'beetroot' ? crop * 2 / 3 : crop
}

// One second of a tracked crop's growth (`tracked` forgets it when it is no crop any more).
async function grow (serv, tracked, pos) {
  const reg = serv.registry
  const world = serv.overworld
  const block = await world.getBlock(pos)
  const g = GROWTH[block.name]
  if (!g) { tracked.delete(`${pos.x},${pos.y},${pos.z}`); return }
  if (g.attachedTo) return detach(serv, world, pos, block, g)
  let steps = 0
  if (serv.pb.cropGrowthChance > 0) {
    steps = serv.pb.random() < serv.pb.cropGrowthChance ? 1 : 0
  } else {
    const k = randomTicks(serv)
    if (k === 0) return
    const chance = await chanceOf(serv, world, pos, g)
    for (let i = 0; i < k; i++) if (serv.pb.random() < chance) steps++
  }
  if (steps === 0) return
  const props = block.getProperties()
  const age = Number(props[g.prop])
  if (age < g.max) {
    const next = Math.min(g.max, age + steps)
    const spare = steps - (next - age)
    if (next !== age) await serv.setBlock(world, pos, stateIdOf(reg, block.name, { ...props, [g.prop]: next }))
    if (spare === 0 || !(g.fruit || g.column)) return
  }
  if (g.fruit) return growFruit(serv, world, pos, g)
  if (g.column) return growColumn(serv, world, pos, block, g)
}

// AttachedStemBlock.updateShape: the fruit it faces is gone, so it is a ripe stem again.
async function detach (serv, world, pos, block, g) {
  const [dx, dz] = FACING[block.getProperties().facing] || [0, 0]
  if ((await nameAt(serv, world, pos.offset(dx, 0, dz))).name === g.attachedTo) return
  await serv.setBlock(world, pos, stateIdOf(serv.registry, g.stem, { age: 7 }))
}

async function growFruit (serv, world, pos, g) {
  const reg = serv.registry
  const [dx, dz, facing] = SIDES[Math.floor(serv.pb.random() * SIDES.length)]
  const target = pos.offset(dx, 0, dz)
  if ((await world.getBlock(target)).name !== 'air') return
  if (!FRUIT_SOIL.includes((await world.getBlock(target.offset(0, -1, 0))).name)) return
  await serv.setBlock(world, target, reg.blocksByName[g.fruit].defaultState)
  await serv.setBlock(world, pos, stateIdOf(reg, g.attached, { facing }))
}

async function growColumn (serv, world, pos, block, g) {
  const reg = serv.registry
  let height = 1
  while (height < g.column && (await world.getBlock(pos.offset(0, -height, 0))).name === block.name) height++
  const above = pos.offset(0, 1, 0)
  if (height >= g.column || (await world.getBlock(above)).name !== 'air') return
  await serv.setBlock(world, above, reg.blocksByName[block.name].defaultState)
  await serv.setBlock(world, pos, stateIdOf(reg, block.name, { age: 0 }))
  serv.pb.crops.track(above)
}

// A plant whose block below is gone breaks and drops (vanilla's canSurvive on a neighbour update):
// sugar cane above a broken cane block (so harvesting the second block of a column also gives the
// third), a crop on broken farmland.
async function popUnsupported (serv, world, pos) {
  const reg = serv.registry
  for (let at = pos.offset(0, 1, 0); ; at = at.offset(0, 1, 0)) {
    const b = await world.getBlock(at)
    if (!GROWTH[b.name] || GROWTH[b.name].attachedTo || b.name === 'cocoa') return
    const drops = serv.pb.dropsFor(b) || []
    await serv.setBlock(world, at, 0)
    serv.pb.spawnDrops(world, at, drops)
    serv.emit('control_event', { event: 'block_popped', pos: [at.x, at.y, at.z], block: b.name, drops: drops.map(d => [reg.items[d.id].name, d.count]) })
    if (b.name !== 'sugar_cane') return
  }
}
