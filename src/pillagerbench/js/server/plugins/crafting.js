'use strict'
// Crafting: the 2x2 grid of the player inventory and the crafting table (3x3), from minecraft-data
// recipes. Taking the result consumes one of each ingredient; containers (milk bucket -> bucket)
// stay in the grid as in vanilla. Shift-click crafts as many as fit.
const { indexRecipes } = require('../recipes')
const { CRAFT_LEFTOVER } = require('../tables')

// A crafting grid inside window w: slots [first, first + side*side), result in slot 0. `craft`: the
// server and what it crafts by ({ serv, reg, Item, match, leftoverId }).
function gridSpec (craft, side, first) {
  const { serv, reg, Item, match, leftoverId } = craft
  const gridSlots = Array.from({ length: side * side }, (_, i) => first + i)
  const recipeOf = (w) => match(gridSlots.map(s => w.slots[s]?.type ?? null), side)
  const refresh = (w) => {
    const r = recipeOf(w)
    const want = r ? new Item(r.result.id, r.result.count) : null
    if (!Item.equal(want, w.slots[0])) w.updateSlot(0, want)
  }
  const consume = (w) => {
    for (const s of gridSlots) {
      const it = w.slots[s]
      if (!it) continue
      if (leftoverId[it.type] && it.count === 1) w.updateSlot(s, new Item(leftoverId[it.type], 1))
      else w.updateSlot(s, it.count > 1 ? new Item(it.type, it.count - 1, it.metadata) : null)
    }
  }
  const takeOnce = (w, player, toCursor) => {
    const r = recipeOf(w)
    if (!r) return false
    const out = new Item(r.result.id, r.result.count)
    if (toCursor) {
      const cur = w.selectedItem
      if (cur && (cur.type !== out.type || cur.count + out.count > cur.stackSize)) return false
      w.selectedItem = new Item(out.type, (cur ? cur.count : 0) + out.count)
    } else {
      const range = Array.from({ length: w.inventoryEnd - w.inventoryStart }, (_, i) => w.inventoryStart + i)
      if (!fits(w, out, range)) return false
      serv.pb.addItem(w, out.type, out.count, range)
    }
    consume(w)
    serv.emit('control_event', { event: 'item_crafted', player: player.username, item: reg.items[out.type].name, count: out.count })
    return true
  }
  return {
    resultSlot: 0,
    gridSlots,
    takeResult (w, click, player) {
      if (click.mode === 1) { while (takeOnce(w, player, false)); } else if (click.mode === 0) takeOnce(w, player, true)
      refresh(w)
    },
    afterClick: refresh,
    returnGrid (w, player) {
      for (const s of gridSlots) {
        const it = w.slots[s]
        if (it) { w.updateSlot(s, null); serv.pb.returnToInventory(player, it) }
      }
      w.updateSlot(0, null)
    }
  }
}

function fits (w, item, range) {
  let room = 0
  for (const s of range) {
    const it = w.slots[s]
    if (!it) room += item.stackSize
    else if (it.type === item.type) room += it.stackSize - it.count
  }
  return room >= item.count
}

module.exports.server = function (serv) {
  const reg = serv.registry
  const Item = require('prismarine-item')(reg)
  const match = indexRecipes(reg.recipes)
  const leftoverId = Object.fromEntries(Object.entries(CRAFT_LEFTOVER).map(([a, b]) => [reg.itemsByName[a].id, reg.itemsByName[b].id]))
  const craft = { serv, reg, Item, match, leftoverId }

  serv.pb.inventoryCraftingSpec = gridSpec(craft, 2, 1)
  const tableGrid = gridSpec(craft, 3, 1)

  serv.once('asap', () => {
    serv.pb.onBlockInteraction('crafting_table', ({ player }) => {
      const spec = {
        type: 'minecraft:crafting',
        title: 'Crafting',
        slots: new Array(10).fill(null),
        takeResult: tableGrid.takeResult,
        afterClick: tableGrid.afterClick,
        onClose: (w, p) => tableGrid.returnGrid(w, p)
      }
      serv.pb.openContainer(player, spec)
      return true
    })
  })
  serv.pb.onInventoryClose = (player) => {
    serv.pb.inventoryCraftingSpec.returnGrid(player.inventory, player)
    if (player.inventory.selectedItem) {
      const it = player.inventory.selectedItem
      player.inventory.selectedItem = null
      serv.pb.returnToInventory(player, it)
    }
  }
}

module.exports.player = function (player, serv) {
  player.pbInventorySpec = serv.pb.inventoryCraftingSpec
}
