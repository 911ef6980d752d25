'use strict'
// Placing, as vanilla 1.16.5 allows it (reach is in reach.js): a block goes only into a space that
// is empty or replaceable (tables.REPLACEABLE: air, water, grass …), against a block that is there
// (a click on air has nothing to place against), and not into a player's or mob's box.
// flying-squid placed blocks anywhere but into the placing player's own feet block. (Vanilla itself
// does not check the clicked block is there, which "air place" cheats use; we do.)
const { REPLACEABLE } = require('../tables')

const RACE_MS = 1000

module.exports.server = function (serv) {
  const reg = serv.registry
  const replaceable = new Set(REPLACEABLE)
  const air = new Set(['air', 'cave_air', 'void_air'])
  const none = { id: -1, data: 0 }
  const where = (p) => `(${p.x}, ${p.y}, ${p.z})`

  // Does an entity's box (width w, height h, feet at its position) overlap the block cell at `pos`?
  const overlaps = (e, pos, w, h) => e.position.x + w / 2 > pos.x && e.position.x - w / 2 < pos.x + 1 &&
    e.position.z + w / 2 > pos.z && e.position.z - w / 2 < pos.z + 1 && e.position.y + h > pos.y && e.position.y < pos.y + 1

  function inTheWay (world, pos) {
    for (const e of Object.values(serv.entities)) {
      if (e.world !== world || (e.type !== 'player' && e.type !== 'mob') || e.dead) continue
      if (e.type === 'player' && e.gameMode === 3) continue
      const w = e.type === 'player' ? 0.6 : (e.width || 0.9)
      const h = e.type === 'player' ? 1.8 : (e.height || 1.4)
      if (overlaps(e, pos, w, h)) return e.type === 'player' ? e.username : e.name
    }
    return null
  }

  // Cells whose block someone dug or placed in the last RACE_MS: a click there acted on a view that
  // was stale by a moment (two players at the same block), a race between honest players rather
  // than a cheat, so it is refused without a report.
  const changed = new Map() // "x,y,z" -> ms
  const key = (p) => `${p.x},${p.y},${p.z}`
  const racing = (p) => Date.now() - (changed.get(key(p)) ?? -Infinity) < RACE_MS
  serv.on('control_event', (e) => {
    if (e.event !== 'block_dug') return
    changed.set(e.pos.join(','), Date.now())
    if (changed.size > 1000) for (const [k, t] of changed) if (Date.now() - t > RACE_MS) changed.delete(k)
  })

  // A survival player's held stack pays for each placement only after it is done (flying-squid
  // takes one off once placeItem returns), so two clicks arriving together both found one item and
  // placed two, and the stack went below zero and on placing. Each placement under way reserves one
  // item of the stack at once; a click that finds nothing left unreserved places nothing, as vanilla
  // (one packet at a time) would. The reservation ends after flying-squid has taken its item off.
  const reserved = new WeakMap() // held stack -> placements under way
  function reserve (player, item) {
    if (!item || !player || player.gameMode !== 0) return () => {}
    const n = reserved.get(item) ?? 0
    if (item.count - n <= 0 || player.inventory.slots[36 + player.heldItemSlot] !== item) return null
    reserved.set(item, n + 1)
    return () => setImmediate(() => reserved.set(item, (reserved.get(item) ?? 1) - 1))
  }

  serv.once('asap', () => {
    const placeItem = serv.placeItem
    serv.placeItem = async (data) => {
      const release = reserve(data.player, data.item)
      if (!release) return none
      try {
        return await checkedPlace(data)
      } finally {
        release()
      }
    }
    async function checkedPlace (data) {
      const { player, placedPosition, referencePosition, item } = data
      // (seeds and other crops: farming.js plants them only onto free soil, silently as vanilla — two
      // players planting the same farmland at once is a race, not a cheat)
      const places = item && reg.blocksByName[item.name]
      if (places && player && (player.gameMode === 0 || player.gameMode === 2)) {
        const ref = await player.world.getBlock(referencePosition)
        const at = await player.world.getBlock(placedPosition)
        let reason = null
        if (air.has(ref.name)) reason = `nothing to place ${item.name} against at ${where(referencePosition)} (air)`
        else if (!replaceable.has(at.name)) reason = `cannot place ${item.name} at ${where(placedPosition)}: ${at.name} is there`
        else if (places.boundingBox === 'block') {
          const who = inTheWay(player.world, placedPosition)
          if (who) reason = `cannot place ${item.name} at ${where(placedPosition)}: ${who} is in the way`
        }
        if (reason) {
          if (!racing(referencePosition) && !racing(placedPosition)) serv.pb.refuse(player, 'place', reason)
          serv.pb.resendBlock(player, placedPosition)
          return none
        }
      }
      const placed = await placeItem(data)
      if (places && placed && reg.blocks[placed.id]) changed.set(key(placedPosition), Date.now())
      return placed
    }
  })
}
