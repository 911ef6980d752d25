'use strict'
// One write per socket per turn of the event loop. minecraft-protocol writes every packet to the
// socket on its own, and each write is a system call. `batchWrites(socket)` corks the socket at its
// first write of a turn and uncorks it right after the turn (setImmediate), so the packets of one
// tick leave in one writev, in the same order and in the same tick. Used by the server
// (server/plugins/batching.js: every entity's moves to every player each tick), not by the bots
// (see js/bot/main.js). See docs/performance.md.
function batchWrites (socket) {
  if (!socket || typeof socket.cork !== 'function' || socket.pbBatched) return
  socket.pbBatched = true
  const write = socket.write
  let corked = false
  const flush = () => { corked = false; socket.uncork() }
  socket.write = function (...args) {
    if (!corked && !socket.destroyed) {
      corked = true
      socket.cork()
      setImmediate(flush)
    }
    return write.apply(this, args)
  }
}

module.exports = { batchWrites }
