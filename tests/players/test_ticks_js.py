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


def test_the_tick_is_declared_once_and_both_languages_read_it():
    """js/clock/tick.json: the game clock (and through it ticks.js and the server's lockstep) and Python's
    TICK_S agree, and no source spells the tick's length as a number of its own."""
    import re

    from pillagerbench.config.game_tick import TICK_MS, TICK_S, TICKS_PER_S
    from pillagerbench.host.node import JS_DIR
    from pillagerbench.server import clock

    out = run_node_script("console.log(JSON.stringify(require(process.argv[1] + '/clock/game_clock.js').TICK_MS))")
    assert out == TICK_MS == round(TICK_S * 1000) and TICKS_PER_S * TICK_MS == 1000 and clock.TICK_S == TICK_S
    spelled = [
        str(p)
        for p in JS_DIR.glob("*/**/*.js")
        if "node_modules" not in p.parts and re.search(r"TICK_MS\s*=\s*\d", p.read_text())
    ]
    assert not spelled, spelled
