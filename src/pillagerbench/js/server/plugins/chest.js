'use strict'
// Chests: 27 slots per position, kept for the match, pre-filled through the control channel.
const { itemByName, ControlError } = require('../util')

module.exports.server = function (serv) {
  const reg = serv.registry
  const Item = require('prismarine-item')(reg)
  const chests = new Map() // "x,y,z" -> Array(27)
  const key = (p) => `${p.x},${p.y},${p.z}`
  const chestAt = (pos) => {
    if (!chests.has(key(pos))) chests.set(key(pos), new Array(27).fill(null))
    return chests.get(key(pos))
  }

  serv.pb.chests = {
    reset: () => chests.clear(),
    set: (pos, items) => {
      if (!items || typeof items !== 'object') throw new ControlError('chest items must be {name: count}')
      const slots = new Array(27).fill(null)
      let i = 0
      for (const [name, count] of Object.entries(items)) {
        const type = itemByName(reg, name).id
        if (!Number.isInteger(count) || count < 0) throw new ControlError(`chest count for ${name} must be a non-negative integer`)
        let left = count
        const size = reg.items[type].stackSize
        while (left > 0) {
          if (i >= 27) throw new ControlError('chest contents do not fit in 27 slots')
          slots[i++] = new Item(type, Math.min(size, left))
          left -= size
        }
      }
      chests.set(key(pos), slots)
      return serv.pb.chests.get(pos)
    },
    get: (pos) => {
      const out = {}
      for (const it of chestAt(pos)) if (it) out[it.name] = (out[it.name] || 0) + it.count
      return out
    },
    add: (pos, name, count) => {
      const type = itemByName(reg, name).id
      const fake = { slots: chestAt(pos), updateSlot (s, it) { this.slots[s] = it } }
      return count - serv.pb.addItem(fake, type, count, Array.from({ length: 27 }, (_, i) => i))
    }
  }

  serv.pb.onBlockInteraction('chest', ({ block, player }) => {
    const pos = block.position.clone()
    const copy = (it) => it ? new Item(it.type, it.count) : null
    serv.pb.openContainer(player, {
      type: 'minecraft:generic_9x3',
      title: 'Chest',
      slots: chestAt(pos),
      beforeClick: (w) => chestAt(pos).forEach((it, i) => w.updateSlot(i, copy(it))),
      afterClick: (w) => { const slots = chestAt(pos); for (let i = 0; i < 27; i++) slots[i] = copy(w.slots[i]) }
    })
    return true
  })
}
