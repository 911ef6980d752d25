"""Code blocks from LLM answers, checked with the real JavaScript parser (acorn in node)."""

from __future__ import annotations

import time

import pytest

from pillagerbench.agents.code import (
    CodeError,
    JSParser,
    check_program,
    extract_code_blocks,
    parse_js,
    programs_from_answer,
)
from pillagerbench.scenarios import make_scenario

MW = make_scenario("mushroom_war").primitives

GOOD = """\
async function clearSlime(bot) {
  await mineBlock(bot, "slime_block", 3, new Vec3(-9, 4, -10), 7)
}

async function main(bot) {
  while (true) {
    await clearSlime(bot)
    bot.chat(`done ${Math.floor(1.5)}`)
    await bot.waitForTicks(20)
  }
}
"""


def answer(*blocks: str, lang: str = "javascript") -> str:
    body = "\n".join(f"Code for player {i}:\n```{lang}\n{b}\n```\n" for i, b in enumerate(blocks))
    return f"Explain: first round.\nPlan: one clears, one harvests.\n{body}"


def test_extract_blocks_in_order_and_tags():
    text = answer("let a = 1", "let b = 2") + "\n```python\nprint(1)\n```\n```js\nlet c = 3\n```"
    assert extract_code_blocks(text) == ["let a = 1", "let b = 2", "let c = 3"]
    assert extract_code_blocks("```\nlet x = 1\n```") == ["let x = 1"]  # untagged only when no tagged
    assert extract_code_blocks("text ```javascript\nlet x = 1\n") == []  # never closed (truncated)
    assert extract_code_blocks("no code here") == []
    assert extract_code_blocks("````JavaScript\nconst s = '```'\n````") == ["const s = '```'"]


def test_parse_reports_functions_calls_and_syntax_errors():
    p = parse_js(GOOD + "\nmain(bot)\n")
    assert p.ok
    assert [(f.name, f.is_async, f.params) for f in p.functions] == [
        ("clearSlime", True, ("bot",)),
        ("main", True, ("bot",)),
    ]
    assert {"mineBlock", "clearSlime", "Vec3", "main"} <= set(p.calls)
    assert {"bot.chat", "bot.waitForTicks", "Math.floor"} <= set(p.members)
    assert len(p.others) == 1 and "main(bot)" in p.others[0]["text"]
    bad = parse_js("async function main(bot) {\n  await mineBlock(bot, 'x'\n}")
    assert not bad.ok and bad.error.startswith("SyntaxError") and bad.line == 3


def test_parser_is_fast_and_survives_a_restart():
    parser = JSParser()
    try:
        parser.parse("let warm = 1")
        t = time.perf_counter()
        for _ in range(50):
            assert parser.parse(GOOD).ok
        assert (time.perf_counter() - t) / 50 < 0.1
        parser._proc.kill()
        parser._proc.wait()
        assert parser.parse(GOOD).ok  # a new process
    finally:
        parser.close()


def test_check_program_keeps_functions_and_calls_the_last_async_bot_function():
    prog = check_program(GOOD + "\nawait main(bot);\nconst stray = 1\n", MW)
    assert prog.entry == "main"
    assert prog.functions == ("clearSlime", "main")
    assert prog.primitives == ("mineBlock",)
    assert len(prog.dropped) == 2 and "stray" not in prog.code
    assert prog.exec_code.rstrip().endswith("await main(bot);")
    assert parse_js(prog.exec_code).ok


@pytest.mark.parametrize(
    "code, reason",
    [
        ("", "empty"),
        ("async function main(bot) { await mineBlock(bot, 'x' }", "does not parse"),
        ("function main(bot) { }", "no entry point"),
        ("async function main(player) { }", "no entry point"),
        ("async function main(bot) { await craftItem(bot, 'bread') }", "not available in this scenario: craftItem"),
        ("async function main(bot) { await harvestWheat(bot, null) }", "not available in this scenario: harvestWheat"),
        ("async function main(bot) { await sleep(1000) }", "defined nowhere: sleep"),
    ],
)
def test_check_program_rejects(code, reason):
    with pytest.raises(CodeError, match=reason):
        check_program(code, MW)


def test_names_defined_in_the_code_or_sandbox_are_fine():
    code = """
    async function main(bot) {
      const wait = (t) => new Promise(r => setTimeout(r, t))
      const { x, y: [z] } = { x: 1, y: [2] }
      await wait(10); parseInt('3'); JSON.stringify({}); await bot.pathfinder.goto(new GoalNear(x, z, 0, 1))
      try { await giveToPlayer(bot, 'red_mushroom', 'Raze') } catch (err) { console.log(err) }
    }"""
    prog = check_program(code, MW)
    assert prog.primitives == ("giveToPlayer",)
    assert check_program("async function main(bot) { await sleep(1) }", MW, reject_undefined=False).warnings


def test_programs_from_answer_one_per_player():
    res = programs_from_answer(answer(GOOD, GOOD), ["Ryn", "Raze"], MW)
    assert res.complete and not res.problems and res.programs[0].entry == "main"

    res = programs_from_answer(answer(GOOD), ["Ryn", "Raze"], MW)
    assert not res.complete and res.programs[1] is None
    assert any("1 code block(s) for 2 players" in p for p in res.problems)
    assert any(p.startswith("Raze: no code block") for p in res.problems)

    res = programs_from_answer(answer(GOOD, "async function main(bot) { craftItem(bot, 'x') }"), ["Ryn", "Raze"], MW)
    assert res.usable == 1 and any(p.startswith("Raze: calls primitive") for p in res.problems)

    res = programs_from_answer("Explain: nothing. Plan: nothing.", ["Ryn", "Raze"], MW)
    assert res.usable == 0 and res.problems == ["the answer has no ```javascript code block"]

    res = programs_from_answer(answer(GOOD, GOOD, GOOD), ["Ryn", "Raze"], MW)
    assert res.complete and "extra ones were ignored" in res.problems[0]
