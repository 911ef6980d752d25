'use strict'
// Two hot spots of the libraries that the server and every bot run, each replaced by an equivalent that
// does less work (tests/players/test_speedups.py checks they answer the same; docs/performance.md):
// - minecraft-protocol's Splitter reads each packet's length with protodef's readVarInt, which throws
//   an Error (stack trace and all) at the end of every chunk the socket reads, caught at once: about a
//   twentieth of the server's work. Ours reads the same lengths and stops there without throwing.
// - minecraft-data's export parses the version string on every call before it looks in its cache, and
//   prismarine-physics calls it for every physics step of every simulated player. Ours remembers the
//   answer for each version: the very object the library would return.
// Installed by js/server/main.js and js/bot/main.js before anything else loads these libraries.
const LEGACY_PING = 0xfe

function install () {
  rememberedVersions()
  splitterWithoutThrows()
}

function rememberedVersions () {
  const id = require.resolve('minecraft-data')
  const stock = require(id)
  if (stock.pbRemembered) return
  const seen = new Map()
  const data = function (version, preNetty) {
    const key = `${version}\0${preNetty || false}`
    if (!seen.has(key)) seen.set(key, stock(version, preNetty))
    return seen.get(key)
  }
  Object.assign(data, stock, { pbRemembered: true })
  require.cache[id].exports = data
}

// A packet's length at `offset`: {value, size}, or null where protodef's readVarInt would throw (the
// chunk ends within it, or it is longer than 64 bits).
function varInt (buffer, offset) {
  let value = 0
  let shift = 0
  let cursor = offset
  while (true) {
    if (cursor >= buffer.length) return null
    const byte = buffer[cursor]
    value |= (byte & 0x7F) << shift
    cursor++
    if (!(byte & 0x80)) return { value, size: cursor - offset }
    shift += 7
    if (shift > 64) return null
  }
}

function splitterWithoutThrows () {
  const proto = Object.getPrototypeOf(require('minecraft-protocol/src/transforms/framing').createSplitter())
  if (proto.pbWithoutThrows) return
  const stock = proto._transform
  proto._transform = function (chunk, enc, cb) {
    const first = this.buffer.length ? this.buffer[0] : chunk[0]
    if (this.recognizeLegacyPing && first === LEGACY_PING) return stock.call(this, chunk, enc, cb)
    this.buffer = Buffer.concat([this.buffer, chunk])
    let offset = 0
    let next = varInt(this.buffer, offset)
    while (next !== null && this.buffer.length >= offset + next.size + next.value) {
      this.push(this.buffer.slice(offset + next.size, offset + next.size + next.value))
      offset += next.size + next.value
      next = varInt(this.buffer, offset)
    }
    this.buffer = this.buffer.slice(offset)
    return cb()
  }
  proto.pbWithoutThrows = true
}

module.exports = { install }
