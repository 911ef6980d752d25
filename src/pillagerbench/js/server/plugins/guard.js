'use strict'
// Robustness: an exception in any packet handler (ours or flying-squid's) must never kick players
// (flying-squid turns uncaught handler errors into "Internal server error" for everyone).
module.exports.player = function (player, serv) {
  const client = player._client
  const emit = client.emit
  client.emit = function (event, ...args) {
    try {
      return emit.call(this, event, ...args)
    } catch (err) {
      serv.emit('pluginError', err, `packet ${String(event)} from ${player.username}`)
      return true
    }
  }
}

module.exports.server = function (serv) {
  serv.on('pluginError', (err, where) => {
    console.error(`[guard] error in ${where}: ${err && err.stack ? err.stack : err}`)
  })
  // Wrap a handler so that errors (sync or async) are reported instead of thrown.
  serv.guarded = (where, fn) => function (...args) {
    try {
      const r = fn.apply(this, args)
      if (r && typeof r.catch === 'function') return r.catch(err => { serv.emit('pluginError', err, where) })
      return r
    } catch (err) {
      serv.emit('pluginError', err, where)
    }
  }
}
