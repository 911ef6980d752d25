"""The bot runtime's tick wait (js/bot/ticks.js) in the real Node, against a fake bot.

mineflayer stops emitting 'physicsTick' while the chunk under the bot is not loaded, and its own
bot.waitForTicks then rejects after 5 s; a teleport into a chunk the server is slow to send made
`reset` fail in CI that way. Our wait must end in both cases.
"""

from __future__ import annotations

from tests.support.node_script import run_node_script

SCRIPT = r"""
const { EventEmitter } = require('events')
const { waitTicks } = require(process.argv[1] + '/bot/ticks.js')
async function timed (bot, n) { const t = Date.now(); await waitTicks(bot, n); return Date.now() - t }
;(async () => {
  const silent = new EventEmitter()
  const ticking = new EventEmitter()
  const timer = setInterval(() => ticking.emit('physicsTick'), 5)
  const out = {
    silent_ms: await timed(silent, 4),
    ticking_ms: await timed(ticking, 4),
    zero_ms: await timed(silent, 0),
    listeners_left: silent.listenerCount('physicsTick') + ticking.listenerCount('physicsTick')
  }
  clearInterval(timer)
  console.log(JSON.stringify(out))
})()
"""


def test_wait_ticks_ends_without_physics_ticks_and_early_with_them():
    out = run_node_script(SCRIPT)
    assert 4 * 50 <= out["silent_ms"] < 5000  # wall-clock fallback, not mineflayer's 5 s rejection
    assert out["ticking_ms"] < out["silent_ms"]  # 4 ticks at 5 ms each end it before the fallback
    assert out["zero_ms"] < 50
    assert out["listeners_left"] == 0
