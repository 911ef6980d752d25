"""On the lockstep clock a path search's budget is counted in steps, not in the machine's time
(js/clock/game_clock.js, READ_COST_MS): the 7 ms per tick of js/bot/main.js are 140 nodes, what the real
clock's bots searched per tick when the suite's reference figures were measured, and a search that
cannot reach its goal ends at the 2 s think timeout after 40 ticks of them, on any machine."""

from __future__ import annotations

from tests.support.node_script import run_node_script

SCRIPT = r"""
const clock = require(process.argv[1] + '/clock/game_clock.js')
clock.install('lockstep')
const { EventEmitter } = require('events')
const { Vec3 } = require('vec3')
const registry = require('minecraft-data')('1.19.4')
const Chunk = require('prismarine-chunk')('1.19.4')
const World = require('prismarine-world')('1.19.4')
const { goals } = require('mineflayer-pathfinder')
const AStar = require('mineflayer-pathfinder/lib/astar')
const { defaultMovements } = require(process.argv[1] + '/bot/movements.js')

const world = new World(null).sync
const state = (name) => registry.blocksByName[name].defaultState
for (let cx = -2; cx <= 2; cx++) for (let cz = -2; cz <= 2; cz++) {
  const chunk = new Chunk({ minY: -64, worldHeight: 384 })
  for (let x = 0; x < 16; x++) for (let z = 0; z < 16; z++) {
    chunk.setBlockStateId(new Vec3(x, 3, z), state('grass_block'))
    if ((cx * 16 + x) % 6 === 0) chunk.setBlockStateId(new Vec3(x, 4, z), state('red_mushroom_block'))
  }
  world.setColumn(cx, cz, chunk)
}
const bot = new EventEmitter()
Object.assign(bot, { registry, world, version: '1.19.4', blockAt: (p) => world.getBlock(p), game: { minY: -64, height: 384 } })
bot.entity = { position: new Vec3(1.5, 4, 1.5), width: 0.6, height: 1.8, name: 'player', type: 'player' }
bot.entities = { 0: bot.entity }
bot.inventory = { items: () => [] }
bot.pathfinder = { bestHarvestTool: () => null }

;(async () => {
  const m = defaultMovements(bot)
  m.updateCollisionIndex()
  // unreachable: a block in the air; 2000 ms in all, 7 ms a tick (as main.js sets them)
  const search = new AStar(new Vec3(1, 4, 1), m, new goals.GoalBlock(0, 30, 0), 2000, 7, -1)
  const slices = []
  let result
  do {
    const before = search.closedDataSet.size
    result = search.compute()
    slices.push(search.closedDataSet.size - before)
    await clock.advance(clock.TICK_MS)
  } while (result.status === 'partial')
  console.log(JSON.stringify({ slices, status: result.status }))
})()
"""


def test_a_search_visits_the_real_clocks_nodes_per_tick_and_stops_at_the_think_timeout():
    out = run_node_script(SCRIPT)
    full = out["slices"][:-1]  # the last one stops at the timeout
    assert out["status"] == "timeout", out
    assert set(full) == {140}, out["slices"]  # 700 at 5 µs a reading: five times the real clock's search
    assert len(out["slices"]) in (40, 41), len(out["slices"])  # 2 s of game time, 50 ms a tick
