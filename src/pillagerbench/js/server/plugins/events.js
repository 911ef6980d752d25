'use strict'
// Pushes player joins, leaves and chat to the control channel.
module.exports.player = function (player, serv) {
  player.on('spawned', () => serv.emit('control_event', { event: 'player_joined', player: player.username }))
  player.on('disconnected', () => {
    serv.pb.closeContainer?.(player)
    serv.emit('control_event', { event: 'player_left', player: player.username })
  })
  player.on('chat', ({ message }) => serv.emit('control_event', { event: 'chat', player: player.username, message }))
}
