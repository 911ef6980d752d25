'use strict'
// Window clicks, server-authoritative. Replaces flying-squid's click handling for every window:
// - the item a click acts on is read from the server's own slots, never from the packet (a client
//   claiming an item it does not have gets nothing);
// - 1.16 needs a `transaction` confirmation for every click; after it the full window is re-sent;
// - containers (crafting table, furnace, chest) are views: slots [0, inventoryStart) belong to the
//   container, the rest mirror the player's inventory slots 9..44;
// - clicking outside the window tosses the cursor stack; drop-key clicks drop from a slot.
// Crafting/furnace/chest plugins register container kinds through serv.pb.openContainer.
const { Vec3 } = require('vec3')
const { PICKUP } = require('../tables')

const SUPPORTED_MODES = new Set([0, 1, 4])

module.exports.server = function (serv) {
  const Item = require('prismarine-item')(serv.registry)
  const windows = require('prismarine-windows')(serv.registry)
  serv.pb = serv.pb || {}

  // Spawn an item entity thrown by a player, in the direction they look.
  serv.pb.dropItem = (player, type, count) => {
    const yaw = (player.yaw * 360 / 256) * Math.PI / 180
    const pitch = (player.pitch * 360 / 256) * Math.PI / 180
    const dir = new Vec3(-Math.sin(yaw) * Math.cos(pitch), -Math.sin(pitch), Math.cos(yaw) * Math.cos(pitch))
    const entity = serv.spawnObject(serv.registry.entitiesByName.item.id, player.world, player.position.offset(0, 1.3, 0), {
      velocity: dir.scaled(4).offset(0, 2, 0), itemId: type, itemCount: count, pickupDelayTicks: PICKUP.delayTicks.toss, deathTime: 300000
    })
    entity.thrower = player.username
    serv.emit('control_event', { event: 'item_tossed', player: player.username, item: serv.registry.items[type].name, count, entity: entity.id })
    return entity
  }

  const views = inventoryViews(Item)
  const containers = containerWindows(serv, windows, views)
  serv.pb.openContainer = containers.openContainer
  serv.pb.closeContainer = containers.closeContainer
  serv.pb.returnToInventory = (player, it) => {
    const left = serv.pb.addItem(player.inventory, it.type, it.count)
    if (left > 0) serv.pb.dropItem(player, it.type, left)
  }
  serv.pb.sendWindow = views.sendWindow
  serv.pb.handleClick = windowClicks(serv, Item, views)
}

// A container's window mirrors the player's inventory slots 9..44 after its own: pulled in before a
// click, pushed back after; a window is sent whole.
function inventoryViews (Item) {
  const clone = (it) => it ? new Item(it.type, it.count, it.metadata, it.nbt) : null

  function pullInventory (player, w) {
    for (let s = 9; s <= 44; s++) w.updateSlot(w.inventoryStart + s - 9, clone(player.inventory.slots[s]))
  }
  function pushInventory (player, w) {
    for (let s = 9; s <= 44; s++) {
      const mine = w.slots[w.inventoryStart + s - 9]
      if (!Item.equal(mine, player.inventory.slots[s])) player.inventory.updateSlot(s, clone(mine))
    }
  }

  function sendWindow (player, w) {
    const windowId = w === player.inventory ? 0 : w.id
    player._client.write('window_items', { windowId, items: w.slots.map(it => Item.toNotch(it)) })
    player._client.write('set_slot', { windowId: -1, slot: -1, item: Item.toNotch(w.selectedItem) })
  }
  return { clone, pullInventory, pushInventory, sendWindow }
}

// Opening and closing containers.
function containerWindows (serv, windows, views) {
  const { clone, pullInventory, pushInventory, sendWindow } = views

  // Container kinds: { type, title, slots (array kept by the owner), takeResult?, beforeClick? (refresh the
  // view from the owner's state), afterClick? (store the view back), onClose? }
  const openContainer = (player, spec) => {
    closeContainer(player)
    player.pbWindowId = (player.pbWindowId % 100) + 1
    const w = windows.createWindow(player.pbWindowId, spec.type, spec.title)
    spec.slots.forEach((it, i) => w.updateSlot(i, clone(it)))
    player.pbContainer = { w, spec }
    pullInventory(player, w)
    player._client.write('open_window', {
      windowId: w.id, inventoryType: windows.windows[spec.type].type, windowTitle: JSON.stringify({ text: spec.title })
    })
    sendWindow(player, w)
    return w
  }

  function closeContainer (player) {
    const c = player.pbContainer
    if (!c) return
    player.pbContainer = null
    pushInventory(player, c.w) // first: onClose may return grid items into the real inventory
    c.spec.onClose?.(c.w, player)
    if (c.w.selectedItem) returnCursor(player, c.w)
  }

  // Items held on the cursor or left in a 2x2/3x3 grid go back to the inventory (or drop if full).
  function returnCursor (player, w) {
    const it = w.selectedItem
    w.selectedItem = null
    const left = serv.pb.addItem(player.inventory, it.type, it.count)
    if (left > 0) serv.pb.dropItem(player, it.type, left)
  }
  return { openContainer, closeContainer }
}

// handleClick(player, click): a window click, applied to the server's own slots.
function windowClicks (serv, Item, views) {
  const { pullInventory, pushInventory, sendWindow } = views

  const handleClick = (player, click) => {
    const { windowId, slot, mouseButton, mode, action } = click
    // (flying-squid's player.inventory window has id 1 internally; on the wire it is window 0)
    const c = windowId === 0 ? { w: player.inventory, spec: player.pbInventorySpec } : player.pbContainer
    const ours = windowId === 0 || (c && c.w.id === windowId)
    player._client.write('transaction', { windowId, action, accepted: true })
    if (!ours) return
    const w = c.w
    if (windowId !== 0) pullInventory(player, w)
    c.spec?.beforeClick?.(w, player)
    const validSlot = slot === -999 || (Number.isInteger(slot) && slot >= 0 && slot < w.slots.length)
    if (validSlot && SUPPORTED_MODES.has(mode) && mouseButton >= 0 && mouseButton <= 1) {
      const serverClick = { windowId, slot, mouseButton, mode, item: slot >= 0 ? w.slots[slot] : null }
      applyClick(player, c, serverClick)
    }
    c.spec?.afterClick?.(w, player)
    if (windowId !== 0) pushInventory(player, w)
    sendWindow(player, w)
  }

  function applyClick (player, c, click) {
    const w = c.w
    if (click.slot === -999) {
      if (mode0(click) && w.selectedItem) {
        const n = click.mouseButton === 0 ? w.selectedItem.count : 1
        serv.pb.dropItem(player, w.selectedItem.type, n)
        w.selectedItem = w.selectedItem.count > n ? new Item(w.selectedItem.type, w.selectedItem.count - n) : null
      }
      return
    }
    if (click.mode === 4) {
      const it = w.slots[click.slot]
      if (!it || click.slot === w.craftingResultSlot) return
      const n = click.mouseButton === 1 ? it.count : 1
      serv.pb.dropItem(player, it.type, n)
      w.updateSlot(click.slot, it.count > n ? new Item(it.type, it.count - n, it.metadata) : null)
      return
    }
    if (click.slot === w.craftingResultSlot && c.spec?.takeResult) return c.spec.takeResult(w, click, player)
    w.acceptClick(click)
  }
  const mode0 = (click) => click.mode === 0
  return handleClick
}

module.exports.player = function (player, serv) {
  player.pbWindowId = 0
  player.pbContainer = null
  // flying-squid's own window_click/close_window listeners are registered by its inventory plugin;
  // remove them once all plugins have run, then handle clicks ourselves.
  setImmediate(() => {
    player._client.removeAllListeners('window_click')
    player._client.removeAllListeners('close_window')
    player._client.on('window_click', serv.guarded('window_click', (click) => serv.pb.handleClick(player, click)))
    player._client.on('close_window', serv.guarded('close_window', ({ windowId }) => {
      if (windowId === 0) serv.pb.onInventoryClose?.(player)
      else if (player.pbContainer && player.pbContainer.w.id === windowId) serv.pb.closeContainer(player)
    }))
  })
}
