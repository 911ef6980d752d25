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


SEARCH = r"""
const { EventEmitter } = require('events')
const { Vec3 } = require('vec3')
const registry = require('minecraft-data')('1.16.5')
const Chunk = require('prismarine-chunk')('1.16.5')
const World = require('prismarine-world')('1.16.5')
const { Movements, goals } = require('mineflayer-pathfinder')
const AStar = require('mineflayer-pathfinder/lib/astar')
const { defaultMovements, fastGetBlock, fastSearch } = require(process.argv[1] + '/bot/movements.js')
const ours = () => { const m = defaultMovements(bot); fastSearch(m, bot); return m } // as on the lockstep clock

// a 3 by 3 chunk floor of stone with walls of stone and fences, some of them open
const world = new World(null).sync
const id = (name) => registry.blocksByName[name].defaultState
for (let cx = -1; cx <= 1; cx++) for (let cz = -1; cz <= 1; cz++) {
  const chunk = new Chunk()
  for (let x = 0; x < 16; x++) for (let z = 0; z < 16; z++) {
    chunk.setBlockStateId(new Vec3(x, 3, z), id('stone'))
    const wx = cx * 16 + x
    const wz = cz * 16 + z
    if (wx % 7 === 0 && wz % 5 !== 0) chunk.setBlockStateId(new Vec3(x, 4, z), id(wz % 3 ? 'stone' : 'oak_fence'))
  }
  world.setColumn(cx, cz, chunk)
}
const bot = new EventEmitter()
const entity = (x, y, z, name) => ({ position: new Vec3(x, y, z), width: 0.6, height: 1.8, name, type: 'player' })
Object.assign(bot, { registry, world, version: '1.16.5', blockAt: (p) => world.getBlock(p) })
bot.entity = entity(-10, 4, -10, 'player')
bot.entities = { 0: bot.entity, 1: entity(3.3, 4, -2.5, 'player'), 2: entity(-4.5, 4, 6.7, 'zombie'), 3: entity(9.5, 4, 9.5, 'item') }
bot.inventory = { items: () => [] }
bot.pathfinder = { bestHarvestTool: () => null }
bot.game = { minY: 0, height: 256 }

function plain () { // ours before the entity index: the stock entity lookup
  const m = new Movements(bot)
  Object.assign(m, { canDig: false, allow1by1towers: false, scafoldingBlocks: [], allowParkour: false })
  m.getBlock = fastGetBlock(m, bot)
  return m
}
function search (m, goal) {
  m.clearCollisionIndex()
  m.updateCollisionIndex()
  const result = new AStar(new Vec3(-10, 4, -10), m, goal, 1e9, 1e9, -1).compute()
  return { status: result.status, visited: result.visitedNodes, path: result.path.map(p => [p.x, p.y, p.z, p.cost]) }
}
const out = []
for (const goal of [new goals.GoalBlock(20, 4, 20), new goals.GoalNear(5, 4, -3, 1), new goals.GoalBlock(10, 9, 10)]) {
  out.push([search(plain(), goal), search(ours(), goal)])
}
const [m, p] = [ours(), plain()]
for (const x of [m, p]) x.updateCollisionIndex()
const counts = []
for (const [x, y, z] of [[3, 4, -3], [3, 5, -3], [-5, 4, 6], [0, 0, 0], [3.5, 4, -3]]) counts.push([m.getNumEntitiesAt(new Vec3(x, y, z), 0, 0, 0), p.getNumEntitiesAt(new Vec3(x, y, z), 0, 0, 0)])
console.log(JSON.stringify({ out, counts, indexed: Object.keys(m.entityIntersections).length }))
"""


def test_the_entity_index_finds_the_same_paths():
    """js/bot/movements.js keys the blocks other entities stand in by a number and caches the loaded
    columns: a search visits the same nodes and finds the same path as with the stock lookups, with
    other players and a mob in the way (and an item, which the stock ignores)."""
    res = run_node_script(SEARCH)
    assert res["indexed"] == 4  # two blocks for each of the player and the zombie; the item is passable
    for stock, ours in res["out"]:
        assert stock["visited"] > 20, stock
        assert ours == stock
    assert [c[0] for c in res["counts"]] == [c[1] for c in res["counts"]]
    assert any(c[0] > 0 for c in res["counts"])  # some of the probes stand in an entity
