"""Unit checks of the plugin's pure rule code (recipes matcher, drop counts), run in the real Node."""

from __future__ import annotations

from tests.support.node_script import run_node_script

SCRIPT = r"""
const { indexRecipes } = require(process.argv[1] + '/server/recipes.js')
const { rollCount } = require(process.argv[1] + '/server/util.js')
const { seededRandom } = require(process.argv[1] + '/clock/random.js')
const { BLOCK_DROPS } = require(process.argv[1] + '/server/tables.js')
const reg = require('prismarine-registry')('1.16.5')
const id = (n) => n ? reg.itemsByName[n].id : null
const match = indexRecipes(reg.recipes)
const name = (r) => r ? reg.items[r.result.id].name + 'x' + r.result.count : null
const out = {}
out.bread_top = name(match(['wheat', 'wheat', 'wheat', null, null, null, null, null, null].map(id), 3))
out.bread_bottom = name(match([null, null, null, null, null, null, 'wheat', 'wheat', 'wheat'].map(id), 3))
out.two_wheat = name(match(['wheat', 'wheat', null, null, null, null, null, null, null].map(id), 3))
out.bowl = name(match(['oak_planks', null, 'oak_planks', null, 'oak_planks', null, null, null, null].map(id), 3))
out.bowl_shifted_down = name(match([null, null, null, 'oak_planks', null, 'oak_planks', null, 'oak_planks', null].map(id), 3))
out.pie_any_order = name(match([null, 'egg', null, 'sugar', null, 'pumpkin', null, null, null].map(id), 3))
out.stew_2x2 = name(match(['bowl', 'red_mushroom', 'brown_mushroom', null].map(id), 2))
out.cake_in_2x2 = name(match(['milk_bucket', 'milk_bucket', 'sugar', 'egg'].map(id), 2))
out.cookie_mirrored = name(match(['wheat', 'cocoa_beans', 'wheat', null, null, null, null, null, null].map(id), 3))
const rnd = seededRandom(42)
const hist = [0, 0, 0]
for (let i = 0; i < 90000; i++) hist[rollCount(BLOCK_DROPS.red_mushroom_block[0].count, rnd)]++
out.mushroom_hist = hist
console.log(JSON.stringify(out))
"""


def run_js():
    return run_node_script(SCRIPT)


def test_recipe_matching_shaped_shifted_mirrored_and_shapeless():
    out = run_js()
    assert out["bread_top"] == out["bread_bottom"] == "breadx1"
    assert out["two_wheat"] is None
    assert out["bowl"] == out["bowl_shifted_down"] == "bowlx4"
    assert out["pie_any_order"] == "pumpkin_piex1"
    assert out["stew_2x2"] == "mushroom_stewx1"
    assert out["cake_in_2x2"] is None
    assert out["cookie_mirrored"] == "cookiex8"


def test_mushroom_block_drops_0_to_2_with_mean_one_third():
    hist = run_js()["mushroom_hist"]
    n = sum(hist)
    assert abs(hist[0] / n - 7 / 9) < 0.01
    assert abs(hist[1] / n - 1 / 9) < 0.01 and abs(hist[2] / n - 1 / 9) < 0.01
    mean = (hist[1] + 2 * hist[2]) / n
    assert abs(mean - 1 / 3) < 0.01
