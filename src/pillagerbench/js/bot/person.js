'use strict'
// A person's input (the `act` op, docs/people.md): what a player's keys and mouse do in the game, done by the
// same mineflayer bot that agents' code drives, inside the person's run (main.js: gate.js drops what acts
// outside a run), so the server judges it by the same checks (reach, dig time, placing, movement).
const { Vec3 } = require('vec3')

const CONTROLS = ['forward', 'back', 'left', 'right', 'jump', 'sprint', 'sneak']
const REACH = 4.5 // survival reach; the server checks it again
const FACES = [[0, -1, 0], [0, 1, 0], [0, 0, -1], [0, 0, 1], [-1, 0, 0], [1, 0, 0]] // mineflayer's face numbers

function inSight (bot) {
  const block = bot.blockAtCursor(REACH)
  if (!block || block.name === 'air') throw new Error('nothing within reach where you look')
  return block
}

const ACTS = {
  controls: (bot, input) => {
    for (const name of CONTROLS) bot.setControlState(name, Boolean((input.controls || {})[name]))
    return 'ok'
  },
  look: async (bot, input) => { await bot.look(Number(input.yaw) || 0, Number(input.pitch) || 0, true); return 'ok' },
  dig: (bot) => {
    const block = inSight(bot)
    if (!bot.canDigBlock(block)) throw new Error(`cannot dig ${block.name} here`)
    bot.dig(block, 'ignore').catch(() => {}) // it ends over time; stop_dig (mouse up) cancels it
    return `digging ${block.name}`
  },
  stop_dig: (bot) => { if (bot.targetDigBlock) bot.stopDigging(); return 'ok' },
  attack: (bot) => {
    const entity = bot.entityAtCursor(3.5)
    if (!entity) throw new Error('nothing to attack where you look')
    bot.attack(entity)
    return `attacked ${entity.name || entity.username}`
  },
  use: async (bot) => {
    const entity = bot.entityAtCursor(3.5)
    if (entity) { await bot.activateEntity(entity); return `used ${entity.name}` }
    const block = inSight(bot)
    const held = bot.heldItem
    const placeable = held && bot.registry.blocksByName[held.name]
    if (!placeable) { await bot.activateBlock(block); return `used ${block.name}` }
    await bot.placeBlock(block, new Vec3(...FACES[block.face]))
    return `placed ${held.name}`
  },
  hotbar: (bot, input) => { bot.setQuickBarSlot(Math.max(0, Math.min(8, Number(input.slot) || 0))); return 'ok' },
  toss: async (bot) => {
    const held = bot.heldItem
    if (!held) throw new Error('nothing in your hand to toss')
    await bot.toss(held.type, held.metadata, 1)
    return `tossed ${held.name}`
  }
}

// One input: {what: controls|look|dig|stop_dig|attack|use|hotbar|toss, and its fields}; its answer, or an
// error saying why the game refused it (shown on the person's page).
async function act (bot, input) {
  const fn = ACTS[input && input.what]
  if (!fn) throw new Error(`unknown input ${JSON.stringify(input && input.what)} (known: ${Object.keys(ACTS).join(', ')})`)
  return fn(bot, input)
}

// What the person's page shows of its player (the `hud` op): the hotbar (9 slots), the held slot, the whole
// inventory by name, health, food and where it looks (the page's mouse starts from there).
function hud (bot) {
  const slot = (item) => (item ? { name: item.name, count: item.count } : null)
  const start = bot.inventory.hotbarStart
  const items = {}
  for (const item of bot.inventory.items()) items[item.name] = (items[item.name] || 0) + item.count
  const { position: p, yaw, pitch } = bot.entity
  return {
    hotbar: bot.inventory.slots.slice(start, start + 9).map(slot),
    selected: bot.quickBarSlot,
    items,
    health: bot.health,
    food: bot.food,
    yaw,
    pitch,
    position: { x: p.x, y: p.y, z: p.z }
  }
}

module.exports = { act, hud, CONTROLS }
