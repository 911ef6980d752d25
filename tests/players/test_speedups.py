"""js/bot/speedups.js replaces two library hot spots with equivalents: the packet splitter that threw
at the end of every chunk read, and minecraft-data's version parse on every call. Both must answer
exactly as the stock ones: the same packets out of any chunking of a stream (partial lengths, a legacy
ping, an over-long length), the same data object."""

from __future__ import annotations

from tests.support.node_script import run_node_script

SCRIPT = r"""
const framing = require('minecraft-protocol/src/transforms/framing')
const [, writeVarInt, sizeOfVarInt] = require('protodef').types.varint

let seed = 7
const rand = (n) => { seed = (seed * 1103515245 + 12345) % 2147483648; return seed % n }
const frame = (body) => { const b = Buffer.alloc(sizeOfVarInt(body.length) + body.length); writeVarInt(body.length, b, 0); body.copy(b, sizeOfVarInt(body.length)); return b }
const bodies = []
for (let i = 0; i < 120; i++) bodies.push(Buffer.from(Array.from({ length: [0, 1, 5, 127, 128, 300, 2000][rand(7)] }, () => rand(256))))
const stream = Buffer.concat(bodies.map(frame))
const chunkings = [[stream.length], [1], [2], [3], [7], [64], [1000]].map(([n]) => n)
const streams = {
  plain: stream,
  legacy: Buffer.from([0xfe, 0x01, 0xfa, 0x00]),
  too_long: Buffer.concat([frame(Buffer.from([1, 2])), Buffer.from([0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x01, 9, 9])])
}
function split (data, size, legacy) {
  const s = framing.createSplitter()
  s.recognizeLegacyPing = legacy
  const got = []
  s.on('data', (b) => got.push(b.toString('hex')))
  for (let i = 0; i < data.length; i += size) s.write(data.slice(i, i + size))
  return { got, left: s.buffer.toString('hex') }
}
function all () {
  const out = []
  for (const [name, data] of Object.entries(streams)) for (const size of chunkings) for (const legacy of [false, true]) out.push([name, size, legacy, split(data, size, legacy)])
  return out
}
const versionsBefore = require('minecraft-data')('1.16.5')
const stock = all()
require(process.argv[1] + '/bot/speedups.js').install()
const ours = all()
const data = require('minecraft-data')
const differ = stock.filter((s, i) => JSON.stringify(s) !== JSON.stringify(ours[i])).map(s => s.slice(0, 3))
console.log(JSON.stringify({
  cases: stock.length,
  packets: stock[0][3].got.length,
  differ,
  replaced: Boolean(Object.getPrototypeOf(framing.createSplitter()).pbWithoutThrows) && Boolean(data.pbRemembered),
  sameData: data('1.16.5') === versionsBefore && data('1.16.5') === data('1.16.5'),
  props: ['Version', 'versions', 'schemas', 'supportedVersions'].every(k => data[k] !== undefined),
  unknown: data('0.0.1') === null
}))
"""


def test_the_speedups_answer_as_the_stock_libraries():
    res = run_node_script(SCRIPT)
    assert res["replaced"]
    assert res["packets"] > 90 and res["cases"] == 42  # empty bodies make no packet
    assert res["differ"] == [], res["differ"]
    assert res["sameData"] and res["props"] and res["unknown"]
