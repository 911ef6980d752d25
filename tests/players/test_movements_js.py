"""The pathfinder's cheaper block lookup (js/bot/movements.js) answers exactly as the stock
`Movements.getBlock` does, for every kind of block the search cares about and for unloaded chunks."""

from __future__ import annotations

from tests.support.node_script import run_node_script

SCRIPT = r"""
const { EventEmitter } = require('events')
const { Vec3 } = require('vec3')
const registry = require('minecraft-data')('1.16.5')
const Chunk = require('prismarine-chunk')('1.16.5')
const World = require('prismarine-world')('1.16.5')
const { Movements } = require('mineflayer-pathfinder')
const { defaultMovements } = require(process.argv[1] + '/bot/movements.js')

const world = new World(null).sync
const chunk = new Chunk()
const names = ['stone', 'grass_block', 'oak_stairs', 'oak_slab', 'oak_fence', 'water', 'lava', 'ladder', 'white_carpet',
  'oak_door', 'sand', 'red_mushroom_block', 'slime_block', 'farmland', 'wheat', 'sweet_berry_bush', 'cobweb', 'chest',
  'snow', 'soul_sand', 'air']
let i = 0
for (let x = 0; x < 16; x++) for (let z = 0; z < 16; z++) for (let y = 0; y < 6; y++) {
  const b = registry.blocksByName[names[(i++) % names.length]]
  chunk.setBlockStateId(new Vec3(x, y, z), b.minStateId + ((x + z) % (b.maxStateId - b.minStateId + 1)))
}
world.setColumn(0, 0, chunk)
const bot = new EventEmitter()
Object.assign(bot, { registry, world, version: '1.16.5', entities: {}, blockAt: (p) => world.getBlock(p) })
const stock = new Movements(bot)
const fast = defaultMovements(bot)
const KEYS = ['replaceable', 'canFall', 'safe', 'physical', 'liquid', 'climbable', 'height', 'openable', 'type', 'name',
  'stateId', 'boundingBox', 'metadata', 'hardness', 'diggable', 'shapes', 'transparent']
const view = (b) => JSON.stringify(Object.fromEntries(KEYS.map(k => [k, b[k]]).concat([['position', b.position ? b.position.toString() : null]])))
let compared = 0
const differ = []
for (let x = -2; x < 18; x++) for (let z = -2; z < 18; z++) for (let y = -1; y < 8; y++) {
  for (const [dx, dy, dz] of [[0, 0, 0], [1, -1, 0], [0, 1, 1]]) {
    const pos = new Vec3(x, y, z)
    const a = view(stock.getBlock(pos, dx, dy, dz))
    const b = view(fast.getBlock(pos, dx, dy, dz))
    compared++
    if (a !== b && differ.length < 5) differ.push([x, y, z, dx, dy, dz, a, b])
  }
}
const p = new Vec3(3, 2, 4)
const t0 = performance.now(); for (let k = 0; k < 20000; k++) stock.getBlock(p, k % 3, 0, 0); const tStock = performance.now() - t0
const t1 = performance.now(); for (let k = 0; k < 20000; k++) fast.getBlock(p, k % 3, 0, 0); const tFast = performance.now() - t1
console.log(JSON.stringify({ compared, differ, nullPos: view(fast.getBlock(null, 0, 1, 0)) === view(stock.getBlock(null, 0, 1, 0)), tStock, tFast }))
"""


def test_fast_get_block_answers_as_the_stock_one():
    out = run_node_script(SCRIPT)
    assert out["compared"] > 10000
    assert out["differ"] == [], out["differ"]
    assert out["nullPos"]
    assert out["tFast"] < out["tStock"]  # the point of it (measured: several times cheaper)
