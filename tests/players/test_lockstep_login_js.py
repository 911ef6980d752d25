"""A bot on the lockstep clock listens for its spawn before the server can answer its login.

mineflayer injects its plugins (the health plugin among them, which turns the first `update_health`
into the bot's `spawn`) from a zero-delay timer set in createBot. On the game clock that timer waited
for the bot's first free advance, and on a busy machine the server's answer to the login could be read
first: the bot never spawned (1 start in 40). js/bot/lockstep.js runs the timer as it attaches."""

from __future__ import annotations

from tests.support.node_script import run_node_script

SCRIPT = r"""
const clock = require(process.argv[1] + '/clock/game_clock.js')
clock.install('lockstep')
const net = require('net')
const server = net.createServer(() => {}).listen(0, '127.0.0.1', () => {
  const mineflayer = require('mineflayer')
  const bot = mineflayer.createBot({ host: '127.0.0.1', port: server.address().port, username: 'Probe', version: '1.16.5', auth: 'offline', hideErrors: true })
  require(process.argv[1] + '/bot/lockstep.js').attach(bot)
  const listening = bot._client.listenerCount('update_health')  // before any turn of the event loop
  console.log(JSON.stringify({ listening, lockstep: clock.lockstep }))
  process.exit(0)
})
"""


def test_a_lockstep_bot_listens_for_its_spawn_as_it_attaches():
    res = run_node_script(SCRIPT)
    assert res["lockstep"] is True
    assert res["listening"] >= 1  # mineflayer's health plugin, injected before any packet is read
