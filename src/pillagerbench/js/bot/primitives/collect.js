'use strict'
// How upstream's primitives collect (reference §5.12, its modified mineflayer-collectblock), shared by
// mineBlock and the harvest primitives: each time the remaining target nearest to the bot, blocks and
// the drops they spawned alike; walk within 3 of a block (goalNear) or until it is in sight; dig it or
// right-click it, turning to it first at mineflayer's head speed (3 rad/s: mineflayer's default, which
// collectblock's bot.dig(block) uses); wait 10 ticks for its drops; a drop that appears within 0.5 of
// the block's centre becomes a target, picked up by walking onto it (skipped after 10 s).
const AFTER_DIG_TICKS = 10
const DROP_RADIUS = 0.5
const PICKUP_TIMEOUT_MS = 10000

function collector (ctx, h) {
  const { bot, run, goals } = ctx

  const gone = (e) => bot.entities[e.id] !== e || e.isValid === false

  async function pickUp (entity) {
    const deadline = Date.now() + PICKUP_TIMEOUT_MS
    try {
      bot.pathfinder.setGoal(new goals.GoalFollow(entity, 0), true)
      while (!gone(entity) && Date.now() < deadline) await h.waitTicks(1)
    } finally {
      bot.pathfinder.setGoal(null)
    }
    if (!gone(entity)) ctx.chat('Failed to pickup item! Skip it!')
  }

  // positions: blocks to take; act(block): dig or right-click. Returns how many blocks were taken.
  async function collect (positions, { goalNear = true, act }) {
    const blocks = [...positions]
    // as collectblock: a target is still taken if its block has the type it had when found (a crop
    // replanted meanwhile is broken, a bush picked meanwhile right-clicked)
    const kind = new Map(blocks.map(p => [p, bot.blockAt(p)?.type]))
    const isTarget = (p, b) => Boolean(b) && b.type === kind.get(p)
    const drops = []
    let digging = null
    // mineflayer emits itemDrop again on every metadata update of the item: a drop is a target once
    // (collectblock's Targets.appendTarget ignores one it holds), or an unreachable one costs 10 s each time
    const onDrop = (e) => { if (digging && !drops.includes(e) && e.position.distanceTo(digging) <= DROP_RADIUS) drops.push(e) }
    bot.on('itemDrop', onDrop)
    let taken = 0
    try {
      while (blocks.length || drops.length) {
        const at = bot.entity.position
        const dist = (t) => (t.position ? t.position : t.offset(0.5, 0.5, 0.5)).distanceSquared(at)
        const all = [...blocks, ...drops]
        const next = all.reduce((a, b) => (dist(b) < dist(a) ? b : a))
        if (next.position) { // a drop
          drops.splice(drops.indexOf(next), 1)
          if (!gone(next)) await pickUp(next)
          continue
        }
        blocks.splice(blocks.indexOf(next), 1)
        if (!isTarget(next, bot.blockAt(next))) continue
        await h.goto(goalNear ? h.near(next, 3) : new goals.GoalLookAtBlock(next, bot.world))
        const block = bot.blockAt(next)
        if (!isTarget(next, block)) continue
        // out of reach (the server refuses digs more than 6 blocks from the eyes, vanilla's reach): skip it
        if (bot.entity.position.offset(0, 1.5, 0).distanceTo(next.offset(0.5, 0.5, 0.5)) > 5.9) continue
        digging = next.offset(0.5, 0.5, 0.5)
        let done = false
        try {
          done = await act(block) !== false
        } catch (err) {
          if (h.isStop(err) || !run.active) throw err
        }
        if (done) {
          taken++
          await h.waitTicks(AFTER_DIG_TICKS)
        }
        digging = null
      }
    } finally {
      bot.removeListener('itemDrop', onDrop)
    }
    return taken
  }

  return { collect }
}

module.exports = { collector, AFTER_DIG_TICKS }
