'use strict'
// Reach, as vanilla 1.16.5 checks it (tables.REACH, maths in ../limits.js):
// - digging: refused when the block's centre is more than 6 blocks from the player's eyes;
// - using or placing against a block (right-click: chests, furnaces, crafting tables, hoes, seeds,
//   blocks): refused unless the clicked block's centre is within 8 blocks of the feet;
// - attacking or using an entity: refused unless it is within 6 blocks of the feet;
// - an open container window closes (as vanilla's stillValid, every tick) when its player is more
//   than 8 blocks from the container.
// Only survival and adventure players are checked (creative and spectator watchers are not).
const { Vec3 } = require('vec3')
const { digTooFar, useTooFar, containerTooFar, entityTooFar } = require('../limits')
const { PLANTING } = require('../tables')

const CONTAINERS = ['chest', 'furnace', 'crafting_table'] // a right-click on them opens them, whatever is held

const checked = (player) => player.gameMode === 0 || player.gameMode === 2
const where = (p) => `(${p.x}, ${p.y}, ${p.z})`
const blocks = (d) => `${d.toFixed(1)} blocks`

module.exports.server = function (serv) {
  const nameAt = (world, pos) => {
    const id = world.sync.getBlockStateId(pos)
    return id == null ? 'block' : (serv.registry.blocksByStateId[id]?.name || 'block')
  }
  // Tell the client the block is still there (mineflayer removes it on its side when it finishes).
  const resend = (player, pos) => {
    const id = player.world.sync.getBlockStateId(pos)
    if (id != null) player._client.write('block_change', { location: pos, type: id })
  }
  serv.pb.resendBlock = resend

  serv.pb.gate('block_dig', (player, packet) => {
    if (!checked(player) || !packet || (packet.status !== 0 && packet.status !== 2)) return null
    const pos = new Vec3(packet.location.x, packet.location.y, packet.location.z)
    const key = pos.toString()
    if (packet.status === 2 && player.pbDigRefused === key) { resend(player, pos); return { silent: true } }
    const d = digTooFar(player.position, pos)
    if (d === null) { player.pbDigRefused = null; return null }
    player.pbDigRefused = key
    resend(player, pos)
    return { action: 'dig', reason: `too far to dig ${nameAt(player.world, pos)} at ${where(pos)} (${blocks(d)} from the eyes; at most 6)` }
  })

  serv.pb.gate('block_place', (player, packet) => {
    if (!checked(player) || !packet || !packet.location) return null
    const pos = new Vec3(packet.location.x, packet.location.y, packet.location.z)
    const d = useTooFar(player.position, pos)
    if (d === null) return null
    const name = nameAt(player.world, pos)
    const held = player.inventory.slots[36 + player.heldItemSlot]
    const placing = !CONTAINERS.includes(name) && held && (serv.registry.blocksByName[held.name] || PLANTING[held.name])
    return placing
      ? { action: 'place', reason: `too far to place against ${name} at ${where(pos)} (${blocks(d)}; less than 8)` }
      : { action: 'use_block', reason: `too far to use ${name} at ${where(pos)} (${blocks(d)}; less than 8)` }
  })

  serv.pb.gate('use_entity', (player, packet) => {
    if (!checked(player) || !packet) return null
    const target = serv.entities[packet.target]
    if (!target || target.world !== player.world) return null
    const d = entityTooFar(player.position, target.position)
    if (d === null) return null
    if (packet.mouse === 2) return { silent: true } // the "interact at" twin of a use (mouse 0) packet: counted once
    const what = target.type === 'player' ? target.username : (target.name || 'entity')
    return { action: packet.mouse === 1 ? 'attack' : 'use_entity', reason: `too far to ${packet.mouse === 1 ? 'attack' : 'use'} ${what} (${blocks(d)}; less than 6)` }
  })

  // Remember which block a container window belongs to.
  serv.once('asap', () => {
    const inner = serv.interactWithBlock
    serv.interactWithBlock = async (data) => {
      const before = data.player.pbContainer
      const r = await inner(data)
      const now = data.player.pbContainer
      if (now && now !== before) now.pos = data.block.position.clone()
      return r
    }
  })

  serv.on('tick', serv.guarded('container reach', () => {
    for (const player of serv.players) {
      const c = player.pbContainer
      if (!c || !c.pos || !checked(player)) continue
      const d = containerTooFar(player.position, c.pos)
      if (d === null) continue
      const name = nameAt(player.world, c.pos)
      serv.pb.closeContainer(player)
      player._client.write('close_window', { windowId: c.w.id })
      serv.pb.refuse(player, 'use_block', `walked out of reach of the ${name} at ${where(c.pos)} (${blocks(d)}; at most 8): its window was closed`)
    }
  }))
}
