'use strict'
// PB_TRACE=search: how many nodes each slice of a path search visited (mineflayer-pathfinder's A*
// searches `tickTimeout` ms per tick, then returns 'partial' and goes on at the next tick), logged at
// exit as one line `[search] {"full": [...], "other": n}`: the nodes of every slice that used its whole
// tick, and how many searches ended within one. For benchmarks/search_budget.py, which measured what
// the lockstep clock gives a search per tick (js/clock/game_clock.js, READ_COST_MS).
const AStar = require('mineflayer-pathfinder/lib/astar')

function install (log) {
  const stock = AStar.prototype.compute
  const full = []
  let other = 0
  AStar.prototype.compute = function () {
    const before = this.closedDataSet.size
    const result = stock.call(this)
    if (result.status === 'partial') full.push(this.closedDataSet.size - before)
    else other++
    return result
  }
  process.on('exit', () => log(`[search] ${JSON.stringify({ full, other })}`))
}

module.exports = { install }
