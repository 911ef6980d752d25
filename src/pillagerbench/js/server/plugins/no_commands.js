'use strict'
// Agent players are not operators: every chat command from a player is refused. The game master
// drives the world through the control channel instead. People watching with a real client can be
// named operators (settings.operators, e.g. `pillagerbench server operators=[Steve]`).
module.exports.player = function (player, serv) {
  const allowed = (serv.pb.operators || []).includes(player.username)
  player.op = allowed
  if (allowed) return
  player.handleCommand = async (str) => {
    const name = String(str).split(' ')[0]
    player.chat(`Commands are disabled for players: /${name} refused`)
    serv.emit('control_event', { event: 'command_refused', player: player.username, command: String(str) })
  }
}
