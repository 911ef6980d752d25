'use strict'
// Observations in upstream's shape (reference §3): every event's data holds the state keys
// voxels, status, inventory, nearbyChests, blockRecords; `on*` events add their own key.
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
    const chestId = bot.registry.blocksByName.chest.id
    for (const p of bot.findBlocks({ matching: chestId, maxDistance: 16, count: 64 })) {
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
    for (let x = -8; x <= 8; x++) {
      for (let y = -2; y <= 2; y++) {
        for (let z = -8; z <= 8; z++) {
          const b = bot.blockAt(c.offset(x, y, z), false)
          if (b && b.name !== 'air' && b.name !== 'cave_air' && b.name !== 'void_air') names.add(b.name)
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

module.exports = { Observer, timeOfDayName }
