"""Fixtures for TactiCrafter tests: the fake OpenAI-compatible LLM server on loopback with answers
scripted by role, LLM clients on it, and real episodes (real arena server, real bots, Match)."""

from __future__ import annotations

import json
from pathlib import Path

from pillagerbench.llm.fake_server import FakeLLMServer, Rule
from pillagerbench.scenarios import make_scenario
from pillagerbench.teams import TeamContext
from tests.support.llm import fake_llm, llm_client_fixture  # noqa: F401 - fixtures
from tests.teams.conftest import play_series as play_on_server

# --- scripted answers (Mushroom War, red team) ---------------------------------------------------

GRAPH = [
    ["mineBlock(bot, 'slime_block', 3)", [], ["slime_block"]],
    ["mineBlock(bot, 'red_mushroom_block', 2)", [], ["red_mushroom"]],
    ["placeItem(bot, 'slime_block', bot.entity.position.offset(1, 0, 0))", ["slime_block"], []],
    ["sendSignal(bot, 'Raze')", [], []],
    ["killMob(bot, 'cow', 60)", [], ["beef", "leather"]],
    ["giveToPlayer(bot, 'red_mushroom', 'Raze', 1)", ["red_mushroom"], []],
]
NEW_RELATION = ["mineBlock(bot, 'slime_block', 2, new Vec3(-9, 4, -10), 7)", [], ["slime_block"]]

TACTICS_1 = (
    "Let me think: slime blocks stop regrowth, so one player clears them.\n"
    "[tactics]\n1. Ryn removes slime blocks in the red area.\n"
    "2. Raze harvests red mushroom blocks in the red area.\n[tactics end]"
)
TACTICS_2 = (
    "Last round went fine; keep it and add sabotage.\n[tactics]\n"
    "1. Ryn removes slime blocks in the red area.\n2. Raze harvests red mushroom blocks.\n"
    "3. When the red area is clean, Ryn places slime blocks in the blue area.\n[tactics end]"
)
OPPONENT = "They mine slime and mushrooms.\n[tactics]\n1. Byte and Blink mine slime blocks and brown mushrooms in the blue area.\n[tactics end]"
CRITIC = json.dumps(
    {
        "reasoning": "The bot mined slime and stopped.",
        "success": True,
        "critique": "Keep looping instead of stopping after one pass.",
    }
)

# a program that does one pass and ends (so the agent iterates)
ONE_PASS = """\
async function onePass(bot) {
  const home = new Vec3(-9, 4, -10)
  bot.chat("Clearing slime once")
  await mineBlock(bot, "slime_block", 1, home, 7)
}"""
LOOP = """\
async function keepFarming(bot) {
  const home = new Vec3(-9, 4, -10)
  while (true) {
    if (blockExists(bot, "slime_block", home, 7)) await mineBlock(bot, "slime_block", 2, home, 7)
    if (blockExists(bot, "red_mushroom_block", home, 7)) await mineBlock(bot, "red_mushroom_block", 2, home, 7)
    await bot.waitForTicks(20)
  }
}"""
THROWS = """\
async function main(bot) {
  throw new Error("boom at once")
}"""


def code_answer(code: str) -> str:
    return f"Explain: first run.\nPlan:\n1. Follow the tactics.\nCode:\n```javascript\n{code}\n```"


NO_CODE = "Explain: I am not sure.\nPlan:\n1. Think more.\nCode: (none)"


def good_rules(model: str | None = None, *, first_action: str = ONE_PASS) -> list[Rule]:
    """A well-behaved model: every role answers usably; the first code of each player does one
    pass (so it iterates), later code loops."""
    return [
        Rule(role="causal", model=model, match="The causal graph so far", reply=json.dumps([NEW_RELATION])),
        Rule(role="causal", model=model, reply=json.dumps(GRAPH)),
        Rule(role="opponent", model=model, reply=OPPONENT),
        Rule(role="tactics", model=model, match="A round has been played", reply=TACTICS_2),
        Rule(role="tactics", model=model, reply=TACTICS_1),
        Rule(role="critic", model=model, reply=CRITIC),
        Rule(role="action", model=model, match="No code yet.", reply=code_answer(first_action)),
        Rule(role="action", model=model, reply=code_answer(LOOP)),
    ]


llm_client = llm_client_fixture("llm.max_tokens=2000")


def context(
    tmp_path: Path, llm, *, episode: int = 0, scenario: str = "mushroom_war", observations=None, out: str = "red"
) -> TeamContext:
    sc = make_scenario(scenario)
    return TeamContext(
        scenario=sc,
        side=sc.side("red"),
        players={},
        episode=episode,
        out_dir=tmp_path / out,
        observations=observations or {},
        llm=llm,
    )


def requests_of(server: FakeLLMServer, role: str) -> list:
    return [r for r in server.requests if r.role == role]


async def play_series(red, blue, run_dir: Path, **options):
    """Play Mushroom War episodes on a fresh server (tests/teams/conftest.py's play_series: `episodes`,
    `length`, `llms`, `seed`, `clock`, and Match's options)."""
    return await play_on_server("mushroom_war", red, blue, run_dir, **options)
