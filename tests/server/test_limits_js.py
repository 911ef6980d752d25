"""Unit checks of the fair-play maths (js/server/limits.js) with vanilla 1.16.5's numbers, in the real Node."""

from __future__ import annotations

import pytest

from tests.support.node_script import run_node_script

SCRIPT = r"""
const L = require(process.argv[1] + '/server/limits.js')
const { MOVEMENT } = require(process.argv[1] + '/server/tables.js')
const P = (x, y, z) => ({ x, y, z })
const out = {}
// reach: digging from the eyes (feet + 1.5) to the block centre, > 6 refused
out.dig_6_level = L.digTooFar(P(0.5, 4, 0.5), P(6, 5, 0))            // centre (6.5, 5.5, 0.5): exactly 6 from the eyes
out.dig_just_over = L.digTooFar(P(0.5, 4, 0.5), P(6, 5, 1))          // sqrt(37)
out.dig_far_row = L.digTooFar(P(0.5, 4, 0.5), P(16, 4, 6))
// using / placing: feet to the clicked block centre, < 8 allowed (64 refused)
out.use_7_9 = L.useTooFar(P(0.5, 3.5, 0.5), P(7.9, 3, 0))
out.use_8 = L.useTooFar(P(0.5, 3.5, 0.5), P(8, 3, 0))                 // exactly 8: refused (vanilla: < 64)
out.container_8 = L.containerTooFar(P(0.5, 3.5, 0.5), P(8, 3, 0))     // stillValid: <= 64 stays open
out.container_8_1 = L.containerTooFar(P(0.4, 3.5, 0.5), P(8, 3, 0))
// entities: feet to entity position, < 6
out.entity_5_9 = L.entityTooFar(P(0, 4, 0), P(5.9, 4, 0))
out.entity_6 = L.entityTooFar(P(0, 4, 0), P(6, 4, 0))
// dig time: at least 70 %
out.dig_time_70 = L.digTooFast(550, 1000)
out.dig_time_69 = L.digTooFast(549, 1000)
out.dig_time_instant = L.digTooFast(0, 0)
// attack strength: swords 1.6/s -> 12.5 ticks; hand 4/s -> 5 ticks
out.sword_0 = L.attackStrength(0, 'iron_sword')
out.sword_12 = L.attackStrength(12, 'iron_sword')
out.sword_20 = L.attackStrength(20, 'iron_sword')
out.hand_5 = L.attackStrength(5, 'anything_else')
out.scale_0 = L.damageScale(0)
out.scale_half = L.damageScale(0.5)
out.scale_1 = L.damageScale(1)
// movement
const walk = () => {
  const s = L.newMoveState(P(0.5, 4, 0.5), 0)
  const verdicts = []
  let x = 0.5
  for (let i = 1; i <= 100; i++) { x += 0.28; verdicts.push(L.judgeMove(s, P(x, 4, 0.5), 4, i * 50)) } // sprinting, 5.6 blocks/s
  return verdicts.filter(Boolean).length
}
out.sprint_ok = walk()
const jump = () => {
  const s = L.newMoveState(P(0.5, 4, 0.5), 0)
  let y = 4, vy = 0.42, bad = 0
  for (let i = 1; i <= 30; i++) { y = Math.max(4, y + vy); vy = (vy - 0.08) * 0.98; if (L.judgeMove(s, P(0.5 + 0.3 * i, y, 0.5), y <= 4.6 ? 4 : null, i * 50)) bad++ }
  return bad
}
out.jump_ok = jump()
const fall = () => { // walking off a 20-block cliff
  const s = L.newMoveState(P(0.5, 24, 0.5), 0)
  let y = 24, vy = 0, bad = 0
  for (let i = 1; i <= 40 && y > 4; i++) { vy = (vy - 0.08) * 0.98; y = Math.max(4, y + vy); if (L.judgeMove(s, P(0.5, y, 0.5), y <= 4.6 ? 4 : null, i * 50)) bad++ }
  return bad
}
out.fall_ok = fall()
let s = L.newMoveState(P(0.5, 4, 0.5), 0)
out.teleport_16 = L.judgeMove(s, P(-9.5, 4, 6.5), null, 50)
out.up_16 = L.judgeMove(s, P(0.5, 20, 0.5), null, 50)
out.state_unchanged = s.last
// many short moves at once: the speed bucket (10 blocks) runs out
s = L.newMoveState(P(0.5, 4, 0.5), 0)
let x = 0.5, firstRefused = null
for (let i = 1; i <= 40 && firstRefused === null; i++) { x += 0.9; if (L.judgeMove(s, P(x, 4, 0.5), 4, 100)) firstRefused = i }
out.burst_refused_at = firstRefused
// climbing without support, a little at a time
s = L.newMoveState(P(0.5, 4, 0.5), 0)
let climbRefused = null
for (let i = 1; i <= 10 && climbRefused === null; i++) { const y = 4 + 0.3 * i; const v = L.judgeMove(s, P(0.5, y, 0.5), y - 4 <= 0.6 ? 4 : null, i * 50); if (v) climbRefused = [i, v.to] }
out.climb = climbRefused
// hovering at jump height, a move every 50 ms
s = L.newMoveState(P(0.5, 4, 0.5), 0)
let hover = null
for (let i = 1; i <= 100 && hover === null; i++) { const v = L.judgeMove(s, P(0.5, 5, 0.5), null, i * 50); if (v) hover = [i, v.to] }
out.hover = hover
// gliding down slowly: flying
s = L.newMoveState(P(0.5, 30, 0.5), 0)
let glide = null
for (let i = 1; i <= 200 && glide === null; i++) { const v = L.judgeMove(s, P(0.5, 30 - 0.02 * i, 0.5), null, i * 50); if (v) glide = [i, v.to] }
out.glide = glide
out.nan = L.judgeMove(L.newMoveState(P(0, 4, 0), 0), P(NaN, 4, 0), 4, 50)
out.maxStep = MOVEMENT.maxStep
console.log(JSON.stringify(out))
"""


@pytest.fixture(scope="module")
def out():
    return run_node_script(SCRIPT)


def test_reach_uses_vanillas_distances(out):
    assert out["dig_6_level"] is None and out["dig_just_over"] == pytest.approx(37**0.5)
    assert out["dig_far_row"] > 16
    assert out["use_7_9"] is None and out["use_8"] == pytest.approx(8)
    assert out["container_8"] is None and out["container_8_1"] > 8
    assert out["entity_5_9"] is None and out["entity_6"] == pytest.approx(6)


def test_dig_time_tolerance_is_70_percent(out):
    assert out["dig_time_70"] is None and out["dig_time_instant"] is None
    assert "549 ms of the 1000 ms" in out["dig_time_69"]


def test_attack_strength_and_damage_scale(out):
    assert out["sword_0"] == pytest.approx(0.5 / 12.5)
    assert out["sword_12"] == pytest.approx(1.0) and out["sword_20"] == 1
    assert out["hand_5"] == 1
    assert out["scale_0"] == pytest.approx(0.2) and out["scale_half"] == pytest.approx(0.4) and out["scale_1"] == 1


def test_honest_moves_pass(out):
    assert out["sprint_ok"] == 0
    assert out["jump_ok"] == 0
    assert out["fall_ok"] == 0


def test_cheating_moves_are_refused(out):
    assert out["teleport_16"]["to"] == "back" and "moved too quickly" in out["teleport_16"]["reason"]
    assert out["up_16"]["to"] == "back" and "moved up too quickly" in out["up_16"]["reason"]
    assert out["state_unchanged"] == {"x": 0.5, "y": 4, "z": 0.5}
    assert out["burst_refused_at"] == 12  # 11 moves of 0.9 use up the 10-block bucket
    assert out["climb"] == [5, "back"]  # 4 + 1.5 > 4 + 1.35
    assert out["hover"] == [42, "down"]  # 2 s without falling
    assert out["glide"] == [82, "down"]  # 4 s in the air
    assert out["nan"]["to"] == "back"
