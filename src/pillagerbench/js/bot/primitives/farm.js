'use strict'
// Farming (reference §5.9): tillLand, plantCrop and its wrappers, harvest and its wrappers,
// equipBucket, milkCow, destroyCrop.
const { helpers, checkString } = require('./util')
const { collector } = require('./collect')

const UP = [0, 1, 0]
const SIDES = [[1, 0, 0], [-1, 0, 0], [0, 0, 1], [0, 0, -1]]

const TOO_MANY = 'Farming failed too many times, check chat log to see what happened'
const isAir = (b) => b && (b.name === 'air' || b.name === 'cave_air')
const ageOf = (b) => Number((b.getProperties?.() || {}).age ?? 0)

module.exports = {
  name: 'farm',
  make (ctx) {
    const h = helpers(ctx)
    const { collect } = collector(ctx, h)
    const land = farmLand(ctx, h)
    return {
      ...planting(ctx, h, land),
      ...harvesting(ctx, h, land, collect),
      ...milking(ctx, h),
      ...destroying(ctx, land, collect)
    }
  }
}

// What every farming primitive goes by: blockId(name) (an error for no such block) and walkTo(pos, range).
function farmLand (ctx, h) {
  const { bot, mcData } = ctx
  const blockId = (name) => {
    const b = mcData.blocksByName[name]
    if (!b) throw new Error(`No block named ${name}`)
    return b.id
  }

  async function walkTo (pos, range = 3) {
    if (bot.entity.position.distanceTo(pos.offset(0.5, 0.5, 0.5)) > range + 0.5) await h.goto(h.near(pos, range))
    return bot.entity.position.distanceTo(pos.offset(0.5, 0.5, 0.5)) <= 5
  }
  return { blockId, walkTo }
}

// tillLand, plantCrop and its wrappers.
function planting (ctx, h, { blockId, walkTo }) {
  const { bot, run, mcData, Vec3 } = ctx

  // As upstream's: every matching block within 32 with air above (no cap), the hoe equipped once;
  // the chat only when something was tilled.
  async function tillLand (_bot, lands = ['dirt']) {
    const hoe = h.items().find(i => i.name.endsWith('_hoe'))
    if (!hoe) { ctx.chat('No hoe in inventory.'); return }
    await run.race(bot.equip(hoe, 'hand'))
    const ids = lands.map(blockId) // ids, not a function: findBlocks can then skip whole chunk sections
    let tilled = 0
    for (const pos of h.scanBlocks(bot.entity.position, ids)) {
      if (!isAir(bot.blockAt(pos.offset(0, 1, 0)))) continue
      if (!await walkTo(pos)) continue
      await run.race(bot.activateBlock(bot.blockAt(pos), new Vec3(0, 1, 0)))
      tilled++
    }
    if (tilled > 0) ctx.chat('All available land has been tilled.')
  }

  // As upstream's: every block of the lands within 32 (no cap), once for each side in `directions`
  // that is air when the bot gets there, right-clicked on its top face (mineflayer's activateBlock
  // default, as upstream's called it) with the seed in hand. For cocoa that is the log's top, where
  // vanilla places no pod (CocoaBlock needs a jungle log beside the space above): upstream's
  // plantCocoaBeans walked to the logs and kept its beans. It does not stop when the seeds run out:
  // it walks on to the remaining blocks and clicks them with an empty hand, as upstream's did.
  async function plantCrop (_bot, crop, lands, directions = [UP]) {
    checkString(crop, 'crop for plantCrop')
    if (!mcData.itemsByName[crop]) throw new Error(`No item named ${crop}`)
    if (h.itemCount(crop) === 0) { ctx.chat(`No ${crop} in inventory.`); run.fail('farm', TOO_MANY); return }
    const ids = lands.map(blockId)
    const dirs = directions.map(d => h.toVec3(d, 'direction'))
    let clicked = 0
    for (const pos of h.scanBlocks(bot.entity.position, ids)) {
      for (const d of dirs) {
        if (!isAir(bot.blockAt(pos.plus(d)))) continue
        if (!await walkTo(pos)) continue
        const seed = h.findItem(crop)
        if (seed) await run.race(bot.equip(seed, 'hand'))
        await run.race(bot.activateBlock(bot.blockAt(pos)))
        clicked++
      }
    }
    if (clicked > 0) ctx.chat(`All available land has been planted with ${crop}.`)
  }

  const plant = (crop, lands, dirs) => (_bot) => plantCrop(_bot, crop, lands, dirs)
  // the soils upstream's wrappers search (the server would also take grass, as vanilla does)
  const plantSweetBerryBushes = plant('sweet_berries', ['farmland', 'dirt'], [UP])
  const plantWheatSeeds = plant('wheat_seeds', ['farmland'], [UP])
  const plantPotatoes = plant('potato', ['farmland'], [UP])
  const plantCarrots = plant('carrot', ['farmland'], [UP])
  const plantBeetrootSeeds = plant('beetroot_seeds', ['farmland'], [UP])
  const plantMelonSeeds = plant('melon_seeds', ['farmland'], [UP])
  const plantPumpkinSeeds = plant('pumpkin_seeds', ['farmland'], [UP])
  const plantCocoaBeans = plant('cocoa_beans', ['jungle_log'], SIDES)
  const plantSugarCane = plant('sugar_cane', ['dirt', 'sand'], [UP])
  return {
    tillLand, plantCrop, plantSweetBerryBushes, plantWheatSeeds, plantPotatoes, plantCarrots, plantBeetrootSeeds,
    plantMelonSeeds, plantPumpkinSeeds, plantCocoaBeans, plantSugarCane
  }
}

// harvest and its wrappers.
function harvesting (ctx, h, { blockId }, collect) {
  const { bot, run } = ctx

  async function harvest (_bot, pos, crop, goalNear = true, activateBlock = false, matching = () => true) {
    checkString(crop, 'crop for harvest')
    const id = blockId(crop)
    const center = pos ? h.toVec3(pos, 'position for harvest') : bot.entity.position
    const targets = bot.findBlocks({ matching: id, maxDistance: 25, count: 1000, point: center })
      .filter(p => matching(bot.blockAt(p))).slice(0, 20)
    // as upstream's collectblock: always the remaining target nearest to the bot next
    if (targets.length === 0) {
      ctx.chat(`No ${crop} nearby`)
      run.fail('farm', TOO_MANY)
      return
    }
    ctx.chat(`Harvesting ${crop}`)
    // `matching` (ripeness) picks the targets; on arrival collect checks only the type, as
    // collectblock. The chat counts the targets found, as upstream's.
    await collect(targets, {
      goalNear,
      act: (b) => run.race(activateBlock ? bot.activateBlock(b) : bot.dig(b)) // both turn to the block first, as collectblock
    })
    ctx.chat(`Harvested ${targets.length} ${crop}`)
  }

  const ripe = (min) => (b) => ageOf(b) >= min
  const harvestBerries = (_bot, pos) => harvest(_bot, pos, 'sweet_berry_bush', true, true, ripe(2))
  const harvestWheat = (_bot, pos) => harvest(_bot, pos, 'wheat', true, false, ripe(7))
  const harvestPotatoes = (_bot, pos) => harvest(_bot, pos, 'potatoes', true, false, ripe(7))
  const harvestCarrots = (_bot, pos) => harvest(_bot, pos, 'carrots', true, false, ripe(7))
  const harvestBeetroot = (_bot, pos) => harvest(_bot, pos, 'beetroots', true, false, ripe(3))
  const harvestCocoa = (_bot, pos) => harvest(_bot, pos, 'cocoa', false, false, ripe(2))
  const harvestMelons = (_bot, pos) => harvest(_bot, pos, 'melon', false, false) // look-at, as upstream's
  const harvestPumpkins = (_bot, pos) => harvest(_bot, pos, 'pumpkin', false, false)
  const harvestSugarCane = (_bot, groundY) => harvest(_bot, null, 'sugar_cane', true, false, (b) => b.position.y === groundY + 2)
  return {
    harvest, harvestBerries, harvestWheat, harvestPotatoes, harvestCarrots, harvestBeetroot, harvestCocoa, harvestMelons,
    harvestPumpkins, harvestSugarCane
  }
}

// equipBucket, milkCow.
function milking (ctx, h) {
  const { bot, run, goals } = ctx

  async function equipBucket (_bot) {
    const bucket = h.findItem('bucket')
    if (!bucket) { ctx.chat('No bucket in inventory.'); return false }
    await run.race(bot.equip(bucket, 'hand'))
    return true
  }

  async function milkCow (_bot) {
    const cow = bot.nearestEntity(e => e.name === 'cow' && !ctx.observer.dead.has(e.id) && e.position.distanceTo(bot.entity.position) < 48)
    if (!cow) { ctx.chat('No cow nearby, please explore first'); return false }
    if (!h.findItem('bucket')) { ctx.chat('No bucket in inventory.'); return false }
    if (bot.entity.position.distanceTo(cow.position) > 3) await h.goto(new goals.GoalFollow(cow, 2))
    if (!await equipBucket(_bot)) return false
    const before = h.itemCount('milk_bucket')
    await run.race(bot.lookAt(cow.position.offset(0, 1, 0)))
    bot.useOn(cow)
    for (let i = 0; i < 20 && h.itemCount('milk_bucket') <= before; i++) await h.waitTicks(1)
    if (h.itemCount('milk_bucket') <= before) { ctx.chat('Failed to milk cow'); return false }
    ctx.chat('Milked cow')
    return true
  }
  return { equipBucket, milkCow }
}

// destroyCrop.
function destroying (ctx, { blockId }, collect) {
  const { bot, run } = ctx

  // As upstream's: every block of the crop within 32 through collectblock (nearest first, walk
  // within 3, dig, wait for and pick up the drops); silent when there is none.
  async function destroyCrop (_bot, crop) {
    checkString(crop, 'crop for destroyCrop')
    const id = blockId(crop)
    const targets = bot.findBlocks({ matching: id, maxDistance: 32, count: 1000 })
    if (targets.length === 0) return 0
    ctx.chat(`Destroying all ${crop} nearby`)
    return collect(targets, { act: (b) => run.race(bot.dig(b)) })
  }
  return { destroyCrop }
}
