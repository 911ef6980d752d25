"""The gate (js/bot/gate.js) in the real Node, packet by packet: every kind of packet a run's code makes
the player send (dig and its cancel and finish, use on a block, an entity or an item, place, equip,
window clicks and closing, chat, swings, creative slots, sneaking) is dropped when it comes from a run
that is not the current one or has stopped, whenever mineflayer gets round to sending it (a timer, a
promise: the run's context follows), and goes out for the current run; packets of no run's context (the
bot's own physics and plugins) are dropped only when they change the world while no run is active.
tests/players/test_leftovers.py checks the same on the real server for digs, uses and placements."""

from __future__ import annotations

import pytest

from tests.support.node_script import run_node_script

SCRIPT = r"""
const { gate, within, clearLeftovers } = require(process.argv[1] + '/bot/gate.js')
const sent = []
const bot = { _client: { write: (name, params) => sent.push(name + (params.status !== undefined ? ':' + params.status : '')) } }
let current = null
gate(bot, () => current)
const PACKETS = [['block_dig', { status: 0 }], ['block_dig', { status: 1 }], ['block_dig', { status: 2 }],
  ['block_dig', { status: 3 }], ['block_dig', { status: 4 }], ['block_dig', { status: 5 }], ['block_place', {}],
  ['use_entity', {}], ['use_item', {}], ['held_item_slot', {}], ['window_click', {}], ['close_window', {}],
  ['chat', {}], ['arm_animation', {}], ['set_creative_slot', {}], ['entity_action', {}], ['position', {}]]
const name = ([n, p]) => n + (p.status !== undefined ? ':' + p.status : '')
const wait = (ms) => new Promise(resolve => setTimeout(resolve, ms))
async function main () {
  const out = {}
  const a = { active: true }; const b = { active: true }
  current = a
  // run a's code leaves each packet to be sent later (a timer, and a promise after it)
  within(a, () => { for (const [n, p] of PACKETS) setTimeout(() => bot._client.write(n, p), 20) })
  within(a, () => { wait(30).then(() => bot._client.write('block_place', {})) })
  await wait(5)
  a.active = false; current = b // the whistle, then the next episode's run
  await wait(60)
  out.stale = sent.splice(0)
  within(b, () => { for (const [n, p] of PACKETS) bot._client.write(n, p) })
  out.current = sent.splice(0)
  b.active = false
  within(b, () => { for (const [n, p] of PACKETS) bot._client.write(n, p) })
  out.stopped = sent.splice(0)
  for (const [n, p] of PACKETS) bot._client.write(n, p) // no run's context, no active run
  out.outside_idle = sent.splice(0)
  const c = { active: true }; current = c
  for (const [n, p] of PACKETS) bot._client.write(n, p) // no run's context, a run active
  out.outside_active = sent.splice(0)
  // a dig mineflayer still holds is forgotten between runs, its cancel dropped
  current = null
  let held = { position: 1 }
  const digger = { get targetDigBlock () { return held }, stopDigging: () => { bot._client.write('block_dig', { status: 1 }); held = null } }
  clearLeftovers(digger)
  out.leftover = { held, sent: sent.splice(0) }
  out.all = PACKETS.map(name)
  console.log(JSON.stringify(out))
}
main()
"""


@pytest.fixture(scope="module")
def gate():
    return run_node_script(SCRIPT)


def test_no_packet_of_a_stopped_run_reaches_the_next_run(gate):
    # only the bot's movement (not a run's packet) goes out
    assert gate["stale"] == ["position"]


def test_the_current_runs_packets_all_go_out_and_a_stopped_runs_none(gate):
    assert gate["current"] == gate["all"]
    assert gate["stopped"] == ["position"]


def test_packets_of_no_runs_context_are_dropped_only_when_they_change_the_world_with_no_run_active(gate):
    assert gate["outside_active"] == gate["all"]
    world = {
        "block_dig:0",
        "block_dig:1",
        "block_dig:2",
        "block_dig:3",
        "block_dig:4",
        "block_place",
        "use_entity",
        "use_item",
    }
    assert gate["outside_idle"] == [p for p in gate["all"] if p not in world]


def test_a_dig_held_between_runs_is_forgotten_without_a_word_to_the_server(gate):
    assert gate["leftover"] == {"held": None, "sent": []}
