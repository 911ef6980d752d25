'use strict'
// Farm animals: summoned still (no random launch velocity), take damage by the held weapon, die and
// drop their loot; cows can be milked with a bucket; egg farms: each chicken near a chest lays eggs
// into it at vanilla's rate. Velocities sent to clients are clamped (flying-squid's knockback overflowed int16
// and disconnected every client nearby).
const { Vec3 } = require('vec3')
const { MOBS, ATTACK_DAMAGE } = require('../tables')
const { ControlError } = require('../util')
const clock = require('../../clock/game_clock')

const MAX_SPEED = 20 // blocks/s per axis; the protocol's limit is about 81

module.exports.server = function (serv) {
  const reg = serv.registry
  const eggFarms = []

  serv.pb.mobs = {
    summon: (name, pos) => {
      if (!MOBS[name]) throw new ControlError(`unknown mob '${name}' (valid: ${Object.keys(MOBS).join(', ')})`)
      const mob = serv.spawnMob(reg.entitiesByName[name].id, serv.overworld, pos, { velocity: new Vec3(0, 0, 0) })
      farmAnimal(serv, mob)
      return mob.id
    },
    list: () => Object.values(serv.entities).filter(e => e.type === 'mob' && !e.dead)
      .map(e => ({ id: e.id, name: e.name, pos: [e.position.x, e.position.y, e.position.z], health: e.health })),
    removeAll: () => {
      for (const e of Object.values(serv.entities)) if (e.type === 'mob' || e.type === 'object') serv.destroyEntity(e)
    },
    // Each chicken within `radius` of the chest lays an egg into it every intervalS to 2 x intervalS
    // seconds (vanilla Chicken.eggTime: 6000 + random 6000 ticks, so intervalS = 300). A chicken's first
    // egg comes after the time left of a cycle already under way (the world was saved mid-cycle).
    addEggFarm: (chest, intervalS, radius = 6) => {
      if (!(intervalS > 0)) throw new ControlError('egg farm interval_s must be > 0')
      eggFarms.push({ chest, intervalTicks: Math.max(1, Math.round(intervalS * 20)), radius, next: new Map() })
    },
    clearEggFarms: () => { eggFarms.length = 0 }
  }

  serv.on('newEntity', (e) => {
    const send = e.sendVelocity
    e.sendVelocity = (vel, maxVel) => {
      const c = (v) => Math.max(-MAX_SPEED, Math.min(MAX_SPEED, v))
      return send(new Vec3(c(vel.x), c(vel.y), c(vel.z)), maxVel)
    }
  })

  layEggs(serv, eggFarms)
}

// Our animals stand still (no mob AI; flying-squid's physics lifted them off the ground), have
// their real health and die into their loot.
function farmAnimal (serv, e) {
  const reg = serv.registry
  e.velocity = new Vec3(0, 0, 0)
  e.size = null // no physics tick for it (flying-squid's lifted mobs off the ground); spawn packets still work
  e.health = MOBS[e.name].health
  e.takeDamage = serv.guarded('mob damage', ({ damage = 1, attacker } = {}) => {
    if (e.dead) return
    e.health -= damage
    if (e.health > 0) {
      e._writeOthers('entity_status', { entityId: e.id, entityStatus: 2 })
      return
    }
    e.dead = true
    e._writeOthers('entity_status', { entityId: e.id, entityStatus: 3 })
    const drops = MOBS[e.name].loot.map(d => ({ id: reg.itemsByName[d.item].id, count: serv.pb.rollCount(d.count) })).filter(d => d.count > 0)
    serv.pb.spawnDrops(e.world, e.position.floored(), drops, 'mob')
    serv.emit('control_event', {
      event: 'mob_killed', mob: e.name, player: attacker || null,
      drops: drops.map(d => [reg.items[d.id].name, d.count])
    })
    setTimeout(() => serv.destroyEntity(e), 800) // entities.js tells every player
  })
}

// The hens of the egg farms lay, each tick.
function layEggs (serv, eggFarms) {
  // On the lockstep clock hens lay during games only, each one's cycle under way drawn at the game's first
  // tick (from that tick's seeded draws): between games the clock keeps real time's pace, so a cycle
  // counted from the arena's build would lay at a tick the wall clock chose, and its draws would move
  // every other draw of that tick (docs/clock.md). The real clock keeps its cycles from the build.
  let since = null
  function layingNow () {
    if (!clock.lockstep) return true
    if (!serv.pb.clock?.inGame()) return false
    if (since !== serv.pb.tick0) {
      since = serv.pb.tick0
      for (const farm of eggFarms) farm.next.clear()
    }
    return true
  }
  const cycle = (farm) => farm.intervalTicks + Math.floor(serv.pb.random() * (farm.intervalTicks + 1))
  // the time left of a cycle under way: density proportional to P(cycle > t)
  function leftOfCycle (farm) {
    for (;;) {
      const t = serv.pb.random() * 2 * farm.intervalTicks
      const pLonger = t < farm.intervalTicks ? 1 : (2 * farm.intervalTicks - t) / farm.intervalTicks
      if (serv.pb.random() < pLonger) return Math.floor(t)
    }
  }
  serv.on('tick', serv.guarded('egg farms', (delta, tick) => {
    if (eggFarms.length === 0 || !layingNow()) return
    const chickens = Object.values(serv.entities).filter(e => e.name === 'chicken' && !e.dead)
    for (const farm of eggFarms) {
      const at = new Vec3(farm.chest[0] + 0.5, farm.chest[1], farm.chest[2] + 0.5)
      for (const c of chickens) {
        if (c.position.distanceTo(at) > farm.radius) continue
        if (!farm.next.has(c.id)) farm.next.set(c.id, tick + leftOfCycle(farm))
        if (tick < farm.next.get(c.id)) continue
        farm.next.set(c.id, tick + cycle(farm))
        serv.pb.chests.add(new Vec3(...farm.chest), 'egg', 1)
      }
    }
  }))
}

module.exports.player = function (player, serv) {
  const reg = serv.registry
  // The damage of an attack comes from the weapon in hand.
  player.on('attack_cancel', (data) => {
    const held = player.inventory.slots[36 + player.heldItemSlot]
    data.damage = ATTACK_DAMAGE[held?.name] ?? 1
    data.attacker = player.username
    data.velocity = new Vec3(0, 0, 0)
  })
  // Right-click a cow with a bucket in the main hand: milk. As vanilla's, only the "interact" packet
  // milks (ServerGamePacketListenerImpl.handleInteract: "interact at" goes to Entity.interactAt, which a
  // cow passes), once per click, and only for the main hand (the off hand holds nothing here).
  player._client.on('use_entity', serv.guarded('milking', ({ target, mouse, hand }) => {
    if (mouse !== 0 || (hand ?? 0) !== 0) return
    const cow = serv.entities[target]
    const slot = 36 + player.heldItemSlot
    const held = player.inventory.slots[slot]
    if (!cow || cow.name !== 'cow' || cow.dead || held?.name !== 'bucket') return
    if (cow.position.distanceTo(player.position) > 6) return
    serv.pb.removeItem(player.inventory, held.type, 1, [slot])
    const left = serv.pb.addItem(player.inventory, reg.itemsByName.milk_bucket.id, 1)
    if (left) serv.pb.dropItem(player, reg.itemsByName.milk_bucket.id, 1)
    serv.emit('control_event', { event: 'cow_milked', player: player.username })
  }))
}
