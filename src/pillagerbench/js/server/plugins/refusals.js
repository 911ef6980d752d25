'use strict'
// Refused actions, visible: every refusal is pushed to the control channel as
//   {event: 'refused', player, action, reason}      (the match writes it to world_events.jsonl)
// and told to the player in a system chat line "[refused] dig: too far to dig …", which its bot
// reports as an onChat event (so an LLM team's critic reads it). Chat lines are limited to
// CHAT_PER_SECOND per player; the control events are not limited.
//
// Packet gates: serv.pb.gate(packetName, fn) registers fn(player, packet) -> null (let it through)
// or {action, reason} (refused: the packet never reaches flying-squid's handlers or ours) or
// {action, reason, pass: true} (reported, then let through: the gate rewrote the packet into a
// harmless one) or {silent: true} (dropped unreported: the rest of an action already refused).
// A gate that throws is logged and lets the packet through.
const CHAT_PER_SECOND = 4

module.exports.server = function (serv) {
  serv.pb = serv.pb || {}
  const gates = new Map() // packet name -> [fn]
  serv.pb.gate = (packet, fn) => {
    if (!gates.has(packet)) gates.set(packet, [])
    gates.get(packet).push(fn)
  }
  serv.pb.gates = gates

  serv.pb.refuse = (player, action, reason) => {
    serv.emit('control_event', { event: 'refused', player: player.username, action, reason })
    const now = Date.now()
    if (now - (player.pbRefusalChatAt || 0) >= 1000) { player.pbRefusalChatAt = now; player.pbRefusalChats = 0 }
    if (player.pbRefusalChats++ < CHAT_PER_SECOND) {
      try { player.chat(`[refused] ${action}: ${reason}`) } catch (_) {}
    }
  }
}

module.exports.player = function (player, serv) {
  const client = player._client
  const emit = client.emit
  client.emit = function (event, packet, ...rest) {
    const list = serv.pb.gates.get(event)
    if (list) {
      for (const fn of list) {
        let verdict = null
        try { verdict = fn(player, packet) } catch (err) { serv.emit('pluginError', err, `gate ${event} of ${player.username}`) }
        if (!verdict) continue
        if (verdict.silent) return true // the rest of an action already refused
        serv.pb.refuse(player, verdict.action, verdict.reason)
        if (!verdict.pass) return true
        break
      }
    }
    return emit.call(this, event, packet, ...rest)
  }
}
