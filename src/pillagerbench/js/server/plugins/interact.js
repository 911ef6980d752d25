'use strict'
// Right-click on blocks: our handlers by block name, consulted before flying-squid's own.
// A handler returns true when it consumed the click (no block gets placed).
module.exports.server = function (serv) {
  serv.pb = serv.pb || {}
  const handlers = new Map()
  serv.pb.onBlockInteraction = (name, fn) => {
    if (!serv.registry.blocksByName[name]) throw new Error(`onBlockInteraction: unknown block ${name}`)
    handlers.set(name, serv.guarded(`interact ${name}`, fn))
  }
  serv.once('asap', () => {
    const builtin = serv.interactWithBlock
    serv.interactWithBlock = async (data) => {
      const fn = handlers.get(data.block.name)
      if (fn && await fn(data)) return true
      return builtin(data)
    }
  })
}
