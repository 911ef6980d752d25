'use strict'
// Server-side inventory operations (the truth of every slot) and whole-stack pickup.
// Player inventory slots: 0 craft result, 1-4 craft grid, 5-8 armour, 9-35 main, 36-44 hotbar, 45 offhand.
const { itemByName, ControlError } = require('../util')

const STORAGE = [36, 37, 38, 39, 40, 41, 42, 43, 44, ...Array.from({ length: 27 }, (_, i) => 9 + i)]

module.exports.server = function (serv) {
  const Item = require('prismarine-item')(serv.registry)
  serv.pb = serv.pb || {}

  // Add `count` of an item to an inventory window, merging stacks first. Returns how many did not fit.
  function addItem (win, type, count, slots = STORAGE) {
    const stackSize = serv.registry.items[type].stackSize
    for (const s of slots) {
      const it = win.slots[s]
      if (count > 0 && it && it.type === type && it.count < stackSize) {
        const n = Math.min(count, stackSize - it.count)
        win.updateSlot(s, new Item(type, it.count + n, it.metadata, it.nbt))
        count -= n
      }
    }
    for (const s of slots) {
      if (count > 0 && !win.slots[s]) {
        const n = Math.min(count, stackSize)
        win.updateSlot(s, new Item(type, n))
        count -= n
      }
    }
    return count
  }

  function removeItem (win, type, count, slots = STORAGE) {
    let removed = 0
    for (const s of slots) {
      const it = win.slots[s]
      if (removed < count && it && it.type === type) {
        const n = Math.min(count - removed, it.count)
        win.updateSlot(s, it.count - n > 0 ? new Item(type, it.count - n, it.metadata, it.nbt) : null)
        removed += n
      }
    }
    return removed
  }

  serv.pb.STORAGE = STORAGE
  serv.pb.addItem = addItem
  serv.pb.removeItem = removeItem
  serv.pb.give = (player, name, count = 1) => {
    if (!Number.isInteger(count) || count < 1 || count > 64 * 36) throw new ControlError(`count must be an integer 1..2304, got ${JSON.stringify(count)}`)
    const left = addItem(player.inventory, itemByName(serv.registry, name).id, count)
    return { given: count - left, left }
  }
  serv.pb.take = (player, name, count) => removeItem(player.inventory, itemByName(serv.registry, name).id, count ?? Infinity, STORAGE)
  serv.pb.listInventory = (player) => player.inventory.slots
    .map((it, slot) => it ? { slot, name: it.name, count: it.count } : null).filter(Boolean)
  serv.pb.clearInventory = (player) => {
    for (let s = 0; s < player.inventory.slots.length; s++) if (player.inventory.slots[s]) player.inventory.updateSlot(s, null)
    player.inventory.selectedItem = null
  }
}

module.exports.player = function (player, serv) {
  // Pick up the whole stack (flying-squid adds 1 per pickup); record who threw it. Set after
  // flying-squid's own inventory plugin has defined its version.
  setImmediate(() => { player.collect = collect })
  const collect = serv.guarded('collect', (entity) => {
    if (entity.collected || !entity.itemId) return
    const count = entity.itemCount || 1
    const left = serv.pb.addItem(player.inventory, entity.itemId, count)
    const taken = count - left
    if (taken === 0) return
    entity._writeOthersNearby('collect', { collectedEntityId: entity.id, collectorEntityId: player.id, pickupItemCount: taken })
    player._client.write('collect', { collectedEntityId: entity.id, collectorEntityId: player.id, pickupItemCount: taken })
    serv.emit('control_event', {
      event: 'item_picked_up', player: player.username, item: serv.registry.items[entity.itemId].name,
      count: taken, thrower: entity.thrower || null, entity: entity.id
    })
    if (left > 0) { entity.itemCount = left; return }
    entity.collected = true
    entity.destroy()
  })
}
