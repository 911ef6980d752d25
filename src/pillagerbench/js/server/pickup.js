'use strict'
// Pickup geometry (vanilla 1.16), kept apart from the plugin so that it can be tested alone.
const { PICKUP } = require('./tables')

// Does an item entity at `item` (bottom centre) touch the pickup box of a player standing at
// `player` (feet, centre)? Vanilla's AABB.intersects is strict on every face.
function touches (player, item, t = PICKUP) {
  const halfX = t.player.width / 2 + t.reach.horizontal + t.item.width / 2
  const below = t.reach.vertical + t.item.height // the item's top must be above the box's floor
  const above = t.player.height + t.reach.vertical // the item's bottom must be below the box's top
  const dy = item.y - player.y
  return Math.abs(item.x - player.x) < halfX && Math.abs(item.z - player.z) < halfX && dy > -below && dy < above
}

// Fisher-Yates with the given random source (the server's seeded one).
function shuffled (list, random) {
  const out = list.slice()
  for (let i = out.length - 1; i > 0; i--) {
    const j = Math.floor(random() * (i + 1))
    const tmp = out[i]; out[i] = out[j]; out[j] = tmp
  }
  return out
}

module.exports = { touches, shuffled }
