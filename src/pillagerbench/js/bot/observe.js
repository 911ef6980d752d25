'use strict'
// Observations in upstream's shape (reference §3): every event's data holds the state keys
// voxels, status, inventory, nearbyChests, blockRecords; `on*` events add their own key. The fields
// and their types are declared in bot_protocol.json (`observation`, `status`), which Python types them by.
const { Vec3 } = require('vec3')

const EQUIPMENT_SLOTS = [5, 6, 7, 8] // head, chest, legs, feet; then main hand, off hand (45)

function timeOfDayName (t) {
  if (t < 1000) return 'sunrise'
  if (t < 6000) return 'day'
  if (t < 12000) return 'noon'
  if (t < 13000) return 'sunset'
  if (t < 18000) return 'night'
  if (t < 22000) return 'midnight'
  return 'sunrise'
}

const vec = (v) => ({ x: v.x, y: v.y, z: v.z })

// The state id at integer x, y, z read from the chunk data (undefined where no chunk is loaded).
// bot.blockAt builds a whole Block per call (biome, light, block entity); every event's
// observation reads some 1500 positions, so it reads state ids and names them instead.
function stateIdAt (world, p, local) {
  const column = world.getColumnAt(p)
  if (!column) return undefined
  return column.getBlockStateId(local.set(p.x & 15, p.y, p.z & 15))
}

// Positions of blocks whose state id is in `ids` within `radius` of `center` (distance from the
// block's corner, as bot.findBlocks measures it), nearest first, at most `count`; the sections
// searched are those bot.findBlocks searches (within 2 sections, counted along the axes), and a
// section whose palette lacks the block is skipped.
function findStates (bot, ids, center, radius, count) {
  const c = center.floored()
  const reach = Math.ceil((radius + 8) / 16)
  const cs = new Vec3(Math.floor(c.x / 16), Math.floor(c.y / 16), Math.floor(c.z / 16))
  const offset = Math.abs(bot.game.minY >> 4)
  const sections = bot.game.height >> 4
  const local = new Vec3(0, 0, 0)
  const found = []
  for (let dx = -reach; dx <= reach; dx++) {
    for (let dz = -reach; dz <= reach; dz++) {
      const column = bot.world.getColumn(cs.x + dx, cs.z + dz)
      if (!column) continue
      for (let dy = -reach; dy <= reach; dy++) {
        if (Math.abs(dx) + Math.abs(dy) + Math.abs(dz) > reach) continue
        const sy = cs.y + dy + offset
        if (sy < 0 || sy >= sections) continue
        const section = column.sections[sy]
        if (!section || (section.palette && !section.palette.some(s => ids.has(s)))) continue
        const x0 = (cs.x + dx) * 16
        const y0 = sy * 16 + bot.game.minY
        const z0 = (cs.z + dz) * 16
        for (let x = 0; x < 16; x++) {
          for (let y = 0; y < 16; y++) {
            for (let z = 0; z < 16; z++) {
              if (!ids.has(column.getBlockStateId(local.set(x, y0 + y, z)))) continue
              const p = new Vec3(x0 + x, y0 + y, z0 + z)
              if (p.distanceTo(c) <= radius) found.push(p)
            }
          }
        }
      }
    }
  }
  found.sort((a, b) => a.distanceTo(c) - b.distanceTo(c))
  return found.slice(0, count)
}

class Observer {
  constructor (bot) {
    this.bot = bot
    this.blockRecords = new Set()
    this.chests = new Map() // "(x, y, z)" -> {item: count} | "Unknown" | "Invalid"
    this.runStartTick = 0
    this.ticks = 0
    // Mobs the server reported dead (it does not always destroy them for every client).
    this.dead = new Set()
    bot.on('entityDead', (e) => { if (e.type !== 'player') this.dead.add(e.id) })
    bot.on('entityGone', (e) => this.dead.delete(e.id))
    bot.on('physicsTick', () => {
      this.ticks++
      if (this.ticks % 100 === 0) this.sample()
    })
  }

  clear () {
    this.blockRecords.clear()
    this.chests.clear()
  }

  // Every 100 ticks: remember block names seen nearby and chests within 16 blocks.
  sample (voxels = null) {
    const bot = this.bot
    if (!bot.entity) return
    for (const name of (voxels || this.voxels())) this.blockRecords.add(name)
    if (!this.chestStates) {
      const chest = bot.registry.blocksByName.chest
      this.chestStates = new Set(Array.from({ length: chest.maxStateId - chest.minStateId + 1 }, (_, i) => chest.minStateId + i))
    }
    for (const p of findStates(bot, this.chestStates, bot.entity.position, 16, 64)) {
      const key = p.toString()
      if (!this.chests.has(key)) this.chests.set(key, 'Unknown')
    }
  }

  setChest (pos, contents) {
    this.chests.set(new Vec3(pos.x, pos.y, pos.z).toString(), contents)
  }

  voxels () {
    const bot = this.bot
    const names = new Set()
    if (!bot.entity) return []
    const c = bot.entity.position.floored()
    const byState = bot.registry.blocksByStateId
    const p = new Vec3(0, 0, 0)
    const local = new Vec3(0, 0, 0)
    for (let x = -8; x <= 8; x++) {
      for (let y = -2; y <= 2; y++) {
        for (let z = -8; z <= 8; z++) {
          const id = stateIdAt(bot.world, p.set(c.x + x, c.y + y, c.z + z), local)
          if (id === undefined) continue
          const name = byState[id]?.name ?? 'air'
          if (name !== 'air' && name !== 'cave_air' && name !== 'void_air') names.add(name)
        }
      }
    }
    return [...names]
  }

  inventory () {
    const bot = this.bot
    const out = {}
    const win = bot.currentWindow
    const items = win && win !== bot.inventory
      ? win.slots.slice(win.inventoryStart, win.inventoryEnd).filter(Boolean)
      : bot.inventory.items()
    for (const it of items) out[it.name] = (out[it.name] || 0) + it.count
    return out
  }

  status () {
    const bot = this.bot
    const e = bot.entity
    const pos = e ? e.position : new Vec3(0, 0, 0)
    const entities = {}
    if (e) {
      for (const other of Object.values(bot.entities)) {
        if (other === e || other.type === 'player' || other.name === 'item' || !other.name || this.dead.has(other.id)) continue
        const d = other.position.distanceTo(pos)
        if (d < 32 && (entities[other.name] === undefined || d < entities[other.name])) entities[other.name] = d
      }
    }
    const slots = bot.inventory.slots
    const equipment = [...EQUIPMENT_SLOTS.map(s => slots[s]?.name ?? null), bot.heldItem?.name ?? null, slots[45]?.name ?? null]
    let biome = 'None'
    try { biome = bot.blockAt(pos.floored())?.biome?.name || 'None' } catch (_) {}
    let used = 0
    for (let s = 9; s <= 44; s++) if (slots[s]) used++
    return {
      health: bot.health,
      food: bot.food,
      saturation: Number.isFinite(bot.foodSaturation) ? bot.foodSaturation : 5,
      oxygen: Number.isFinite(bot.oxygenLevel) ? bot.oxygenLevel : 20,
      position: vec(pos),
      velocity: e ? vec(e.velocity) : { x: 0, y: 0, z: 0 },
      yaw: e ? e.yaw : 0,
      pitch: e ? e.pitch : 0,
      onGround: e ? e.onGround : false,
      equipment,
      name: bot.username,
      timeSinceOnGround: e ? (e.timeSinceOnGround ?? 0) : 0,
      isInWater: e ? !!e.isInWater : false,
      isInLava: e ? !!e.isInLava : false,
      isInWeb: e ? !!e.isInWeb : false,
      isCollidedHorizontally: e ? !!e.isCollidedHorizontally : false,
      isCollidedVertically: e ? !!e.isCollidedVertically : false,
      biome,
      entities,
      timeOfDay: timeOfDayName(bot.time?.timeOfDay ?? 6000),
      inventoryUsed: used,
      elapsedTime: this.ticks - this.runStartTick
    }
  }

  // The state part of every event.
  observe () {
    const voxels = this.voxels()
    this.sample(voxels)
    const inventory = this.inventory()
    const held = new Set(Object.keys(inventory))
    const chests = {}
    for (const [k, v] of this.chests) chests[k] = v
    return {
      voxels,
      status: this.status(),
      inventory,
      nearbyChests: chests,
      blockRecords: [...this.blockRecords].filter(n => !held.has(n))
    }
  }
}

module.exports = { Observer, timeOfDayName, findStates }
