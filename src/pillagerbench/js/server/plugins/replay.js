'use strict'
// What a replay records, read from the server's own state: one frame holds every player's position,
// facing and held item, the item entities lying in the world, the mobs, and the blocks that changed
// since the last frame (every write to the world passes through `setBlockStateId`, so digging,
// placing, crops growing, the game master's edits and /fill are all seen). Changes are kept only
// while a recording is on; the control op `replay_frame` starts, reads and stops it.
const r2 = (v) => Math.round(v * 100) / 100
const ANGLE = 360 / 256 // flying-squid keeps yaw and pitch as protocol bytes

module.exports.server = function (serv) {
  const reg = serv.registry
  let changes = null // Map "x,y,z" -> [x, y, z, name] while recording, else null
  const listeners = new Set() // (x, y, z, stateId) for every block written (replays, the live view)
  let wrapped = null

  // Call `fn(x, y, z, stateId)` after every block write to the overworld; returns a function that stops it.
  serv.pb.listenBlocks = (fn) => {
    const world = serv.overworld
    if (wrapped !== world) {
      const set = world.setBlockStateId.bind(world)
      world.setBlockStateId = async (pos, stateId) => {
        const result = await set(pos, stateId)
        const x = Math.floor(pos.x); const y = Math.floor(pos.y); const z = Math.floor(pos.z)
        for (const f of listeners) { try { f(x, y, z, stateId) } catch (err) { serv.emit('pluginError', err, 'block listener') } }
        return result
      }
      wrapped = world
    }
    listeners.add(fn)
    return () => listeners.delete(fn)
  }
  function record (x, y, z, stateId) {
    if (changes) changes.set(`${x},${y},${z}`, [x, y, z, reg.blocksByStateId[stateId]?.name ?? 'air'])
  }
  let recording = false
  function watchWorld () {
    if (!recording) { serv.pb.listenBlocks(record); recording = true }
  }

  function held (p) {
    const slot = p.inventory?.slots?.[36 + (p.heldItemSlot || 0)]
    return slot ? reg.items[slot.type]?.name ?? null : null
  }

  serv.pb.replay = {
    // {start: true} begins a recording (changes from now on), {stop: true} ends it after this frame.
    frame: ({ start = false, stop = false } = {}) => {
      if (start) { watchWorld(); changes = new Map() }
      const players = serv.players.filter(p => p.world === serv.overworld && p.gameMode !== 3).map(p => [
        p.username, r2(p.position.x), r2(p.position.y), r2(p.position.z),
        Math.round((p.yaw || 0) * ANGLE), Math.round((p.pitch || 0) * ANGLE), held(p)
      ])
      const items = []
      const mobs = []
      for (const e of Object.values(serv.entities)) {
        if (e.type === 'object' && e.itemId && !e.collected) {
          items.push([e.id, reg.items[e.itemId]?.name, e.itemCount || 1, r2(e.position.x), r2(e.position.y), r2(e.position.z)])
        } else if (e.type === 'mob' && !e.dead) {
          mobs.push([e.id, e.name, r2(e.position.x), r2(e.position.y), r2(e.position.z), e.health])
        }
      }
      const blocks = changes ? [...changes.values()] : []
      if (changes) changes.clear()
      if (stop) changes = null
      return { tick: serv.tickCount, players, items, mobs, blocks }
    }
  }
}
