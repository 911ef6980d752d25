'use strict'
// Furnaces: per-position state (input, fuel, output) that persists for the match; smelting runs on
// server ticks (200 ticks = 10 s per item at 20 TPS) with vanilla burn times; can be pre-filled and
// pre-fuelled through the control channel. Viewers get the progress bars.
const { SMELTING, SMELT_TICKS, FUEL_TICKS, FUEL_LEFTOVER } = require('../tables')
const { itemByName, ControlError } = require('../util')

const describe = (f) => ({
  input: f.slots[0] && [f.slots[0].name, f.slots[0].count],
  fuel: f.slots[1] && [f.slots[1].name, f.slots[1].count],
  output: f.slots[2] && [f.slots[2].name, f.slots[2].count],
  burning: f.burn > 0,
  progress: f.cook / SMELT_TICKS
})

// What smelting goes by (`smelt`): { Item, smeltTo, burnTicks, fuelLeftover }, by item id.
function canSmelt (smelt, f) {
  const { smeltTo } = smelt
  const inp = f.slots[0]
  if (!inp || smeltTo[inp.type] === undefined) return false
  const out = f.slots[2]
  return !out || (out.type === smeltTo[inp.type] && out.count < out.stackSize)
}

// One tick of furnace f; whether its slots changed.
function step (smelt, f) {
  const { Item, smeltTo, burnTicks, fuelLeftover } = smelt
  let changed = false
  if (f.burn > 0) f.burn--
  if (f.burn === 0 && canSmelt(smelt, f) && f.slots[1] && burnTicks[f.slots[1].type]) {
    const fuel = f.slots[1]
    f.burn = f.burnMax = burnTicks[fuel.type]
    f.slots[1] = fuel.count > 1 ? new Item(fuel.type, fuel.count - 1) : (fuelLeftover[fuel.type] ? new Item(fuelLeftover[fuel.type], 1) : null)
    changed = true
  }
  if (f.burn > 0 && canSmelt(smelt, f)) {
    f.cook++
    if (f.cook >= SMELT_TICKS) {
      f.cook = 0
      const inp = f.slots[0]
      const outType = smeltTo[inp.type]
      f.slots[0] = inp.count > 1 ? new Item(inp.type, inp.count - 1) : null
      f.slots[2] = new Item(outType, (f.slots[2] ? f.slots[2].count : 0) + 1)
      changed = true
    }
  } else if (f.cook > 0) {
    f.cook = Math.max(0, f.cook - 2)
  }
  return changed
}

// Every furnace at work steps; its viewers get its slots (when they changed) and the progress bars.
function tickFurnaces (serv, smelt, furnaces) {
  const { Item } = smelt
  for (const f of furnaces.values()) {
    if (f.burn === 0 && !canSmelt(smelt, f) && f.cook === 0) continue
    const changed = step(smelt, f)
    for (const player of f.viewers) {
      const c = player.pbContainer
      if (!c || c.furnace !== f) { f.viewers.delete(player); continue }
      if (changed) {
        f.slots.forEach((it, i) => c.w.updateSlot(i, it ? new Item(it.type, it.count) : null))
        serv.pb.sendWindow(player, c.w)
      }
      const props = [f.burn, f.burnMax, f.cook, SMELT_TICKS]
      props.forEach((value, property) => player._client.write('craft_progress_bar', { windowId: c.w.id, property, value }))
    }
  }
}

// The window of furnace f, opened for player.
function openFurnace (serv, Item, f, player) {
  serv.pb.openContainer(player, {
    type: 'minecraft:furnace',
    title: 'Furnace',
    slots: f.slots,
    beforeClick: (w) => f.slots.forEach((it, i) => w.updateSlot(i, it ? new Item(it.type, it.count) : null)),
    afterClick: (w) => { f.slots = [0, 1, 2].map(i => w.slots[i] ? new Item(w.slots[i].type, w.slots[i].count) : null) },
    onClose: () => f.viewers.delete(player)
  })
  player.pbContainer.furnace = f
  f.viewers.add(player)
}

module.exports.server = function (serv) {
  const reg = serv.registry
  const Item = require('prismarine-item')(reg)
  const byId = (table) => Object.fromEntries(Object.entries(table).map(([k, v]) => [reg.itemsByName[k].id, v]))
  const smeltTo = Object.fromEntries(Object.entries(SMELTING).map(([k, v]) => [reg.itemsByName[k].id, reg.itemsByName[v].id]))
  const burnTicks = byId(FUEL_TICKS)
  const fuelLeftover = Object.fromEntries(Object.entries(FUEL_LEFTOVER).map(([k, v]) => [reg.itemsByName[k].id, reg.itemsByName[v].id]))
  const smelt = { Item, smeltTo, burnTicks, fuelLeftover }
  const furnaces = new Map() // "x,y,z" -> { slots: [input, fuel, output], burn, burnMax, cook, viewers: Set<player> }

  const key = (p) => `${p.x},${p.y},${p.z}`
  function furnaceAt (pos) {
    const k = key(pos)
    if (!furnaces.has(k)) furnaces.set(k, { slots: [null, null, null], burn: 0, burnMax: 0, cook: 0, viewers: new Set() })
    return furnaces.get(k)
  }

  serv.pb.furnaces = {
    reset: () => furnaces.clear(),
    set: (pos, { input = null, fuel = null, output = null } = {}) => {
      const f = furnaceAt(pos)
      const mk = (spec, what) => {
        if (!spec) return null
        const [name, count] = Array.isArray(spec) ? spec : [spec.name, spec.count]
        if (!Number.isInteger(count) || count < 1 || count > 64) throw new ControlError(`furnace ${what} count must be 1..64`)
        return new Item(itemByName(reg, name).id, count)
      }
      f.slots = [mk(input, 'input'), mk(fuel, 'fuel'), mk(output, 'output')]
      f.burn = 0; f.cook = 0
      return describe(f)
    },
    get: (pos) => describe(furnaceAt(pos))
  }

  serv.on('tick', serv.guarded('furnace tick', () => tickFurnaces(serv, smelt, furnaces)))

  serv.pb.onBlockInteraction('furnace', ({ block, player }) => {
    openFurnace(serv, Item, furnaceAt(block.position), player)
    return true
  })
}
