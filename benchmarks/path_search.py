"""The pathfinder's cost per node searched (js/bot/movements.js), in a bot's real Node: a search that
cannot reach its goal explores a 5 by 5 chunk arena of walls, with three other players standing in it,
with the stock Movements, with our block lookup alone (before the entity index and the column cache),
and with ours as the bots use it on the lockstep clock. Prints JSON: microseconds per node visited, the median of --repeats.

    python benchmarks/path_search.py [--repeats 9]

On the lockstep clock a search visits a fixed number of nodes per tick (js/clock/game_clock.js), so a
cheaper node is a faster game and the same game; on the real clock it is more nodes per tick.
"""

from __future__ import annotations

import argparse
import json
import subprocess

from pillagerbench.host.node import JS_DIR, node_binary, node_env

SCRIPT = r"""
const { EventEmitter } = require('events')
const { Vec3 } = require('vec3')
const registry = require('minecraft-data')('1.19.4')
const Chunk = require('prismarine-chunk')('1.19.4')
const World = require('prismarine-world')('1.19.4')
const { Movements, goals } = require('mineflayer-pathfinder')
const AStar = require('mineflayer-pathfinder/lib/astar')
const { defaultMovements, fastGetBlock, fastSearch } = require(process.argv[1] + '/bot/movements.js')
const ours = () => { const m = defaultMovements(bot); fastSearch(m, bot); return m } // as on the lockstep clock
const repeats = Number(process.argv[2])

const world = new World(null).sync
const state = (name) => registry.blocksByName[name].defaultState
for (let cx = -2; cx <= 2; cx++) for (let cz = -2; cz <= 2; cz++) {
  const chunk = new Chunk({ minY: -64, worldHeight: 384 })
  for (let x = 0; x < 16; x++) for (let z = 0; z < 16; z++) {
    for (let y = 0; y < 3; y++) chunk.setBlockStateId(new Vec3(x, y, z), state('stone'))
    chunk.setBlockStateId(new Vec3(x, 3, z), state('grass_block'))
    const wx = cx * 16 + x
    const wz = cz * 16 + z
    if ((wx % 6 === 0 && wz % 9 !== 0) || (wz % 8 === 0 && wx % 5 === 0)) chunk.setBlockStateId(new Vec3(x, 4, z), state('red_mushroom_block'))
  }
  world.setColumn(cx, cz, chunk)
}
const bot = new EventEmitter()
const player = (x, z) => ({ position: new Vec3(x, 4, z), width: 0.6, height: 1.8, name: 'player', type: 'player' })
Object.assign(bot, { registry, world, version: '1.19.4', blockAt: (p) => world.getBlock(p), game: { minY: -64, height: 384 } })
bot.entity = player(1.5, 1.5)
bot.entities = { 0: bot.entity, 1: player(7.5, 3.5), 2: player(-8.5, 12.5), 3: player(15.5, -20.5) }
bot.inventory = { items: () => [] }
bot.pathfinder = { bestHarvestTool: () => null }

const configure = (m) => Object.assign(m, { canDig: false, allow1by1towers: false, scafoldingBlocks: [], allowParkour: false })
const KINDS = {
  stock: () => configure(new Movements(bot)),
  block_lookup_only: () => { const m = configure(new Movements(bot)); m.getBlock = fastGetBlock(m, bot); return m },
  ours
}
const out = {}
for (const [name, make] of Object.entries(KINDS)) {
  const times = []
  let visited = 0
  for (let r = 0; r < repeats; r++) {
    const m = make()
    m.clearCollisionIndex()
    m.updateCollisionIndex()
    const t0 = performance.now()
    const res = new AStar(new Vec3(1, 4, 1), m, new goals.GoalBlock(0, 30, 0), 1e9, 1e9, -1).compute()
    times.push((performance.now() - t0) * 1000 / res.visitedNodes)
    visited = res.visitedNodes
  }
  times.sort((a, b) => a - b)
  out[name] = { us_per_node: Number(times[times.length >> 1].toFixed(2)), nodes: visited }
}
console.log(JSON.stringify(out))
"""


def measure(repeats: int) -> dict:
    """Microseconds per node visited for each kind of Movements, the median of `repeats` searches."""
    cmd = [str(node_binary()), "-e", SCRIPT, str(JS_DIR), str(repeats)]
    proc = subprocess.run(cmd, capture_output=True, text=True, env=node_env(), check=True)
    figures = json.loads(proc.stdout)
    ours, before = figures["ours"]["us_per_node"], figures["block_lookup_only"]["us_per_node"]
    figures["ours_vs_block_lookup_only"] = round(before / ours, 2)
    return figures


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=9)
    args = ap.parse_args()
    print(json.dumps(measure(args.repeats), indent=1))


if __name__ == "__main__":
    main()
