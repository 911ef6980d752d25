"""TactiCrafter's pre-game with the fake LLM provider (no game server): what each module's prompt
holds, role settings, module switches, and every bad answer (retried, recorded, the team goes on)."""

from __future__ import annotations

import json

from pillagerbench.llm.fake_server import Rule
from pillagerbench.players import primitives as prim
from pillagerbench.scenarios import make_scenario
from pillagerbench.teams import make_team
from pillagerbench.teams.tacticrafter import TactiCrafter
from pillagerbench.teams.tacticrafter.events import digest

from .conftest import CRITIC, GRAPH, LOOP, NO_CODE, OPPONENT, TACTICS_1, code_answer, context, good_rules, requests_of

OBS = {
    "Ryn": [
        [
            "observe",
            {
                "voxels": ["slime_block", "red_mushroom_block"],
                "inventory": {"dirt": 2},
                "status": {
                    "position": {"x": -7.5, "y": 4, "z": -9.5},
                    "health": 20,
                    "food": 20,
                    "entities": {"cow": 4.0},
                },
            },
        ]
    ]
}


def record(tmp_path, out="red") -> dict:
    return json.loads((tmp_path / out / "tacticrafter.json").read_text())


def played(team: TactiCrafter) -> None:
    """Pretend an episode was played: events in memory, as post_game leaves them."""
    ryn = [
        ["onChat", {"onChat": "<Ryn> Mined 2 slime_block", "inventory": {"slime_block": 2}}],
        ["onChat", {"onChat": "<Byte> Mined 1 brown_mushroom_block", "inventory": {"slime_block": 2}}],
        ["onChat", {"onChat": "Team blue is clean!", "inventory": {}}],
        ["observe", {"inventory": {"slime_block": 2}, "voxels": ["slime_block"], "status": {}}],
    ]
    team.memory.events = {"Ryn": digest(ryn), "Raze": digest(ryn[3:])}
    team.memory.episodes += 1


async def test_first_episode_prompts_hold_what_the_paper_lists(tmp_path, fake_llm, llm_client):
    fake_llm.add(*good_rules())
    team = make_team("tacticrafter", "mushroom_war")
    await team.pre_game(context(tmp_path, llm_client(), observations=OBS))
    assert [r.role for r in fake_llm.requests[:2]] == ["causal", "tactics"]
    assert not requests_of(fake_llm, "opponent")  # first episode: opponent unknown
    sc = make_scenario("mushroom_war")
    causal = requests_of(fake_llm, "causal")[0].prompt
    assert prim.doc("mineBlock") in causal and prim.doc("giveToPlayer") in causal and sc.description() in causal
    tactics = requests_of(fake_llm, "tactics")[0].messages
    assert sc.description() in tactics[0]["content"] and "red_team" in tactics[0]["content"]
    assert "Action: mineBlock(bot, 'slime_block', 3); Cause: []; Effect ['slime_block']" in tactics[0]["content"]
    assert "[tactics end]" in tactics[0]["content"] and "Ryn, Raze" in tactics[1]["content"]
    actions = requests_of(fake_llm, "action")
    assert len(actions) == 2
    ryn = next(r for r in actions if "You are Ryn" in r.prompt)
    assert len({r.messages[0]["content"] for r in actions}) == 1  # one shared system prompt (caching)
    assert "1. Ryn removes slime blocks in the red area." in ryn.prompt  # the tactics
    assert "cow (4 blocks away)" in ryn.prompt and "red_mushroom_block, slime_block" in ryn.prompt
    assert "Inventory: dirt: 2" in ryn.prompt and prim.doc("mineflayer") in ryn.prompt
    assert team.memory.tactics.startswith("1. Ryn removes") and len(team.memory.graph) == len(GRAPH)
    assert all(a.program is not None for a in team.agents)
    rec = record(tmp_path)
    assert rec["modules"]["causal"]["ok"] and rec["modules"]["tactics"]["step"] == "initial"
    assert rec["llm"]["action"]["calls"] == 2 and rec["roles"]["critic"]["temperature"] == 0.3
    for name in ("tactics.json", "opponent_tactics.json", "causal_graph.json", "code.json"):
        assert (tmp_path / "red" / name).exists()
    assert json.loads((tmp_path / "red" / "opponent_tactics.json").read_text())["opponent_tactics"] == "unknown"


async def test_later_episode_updates_from_last_episodes_events(tmp_path, fake_llm, llm_client):
    fake_llm.add(*good_rules())
    team = make_team("tacticrafter", "mushroom_war")
    client = llm_client()
    await team.pre_game(context(tmp_path, client))
    played(team)
    fake_llm.reset()
    fake_llm.add(*good_rules())
    await team.pre_game(context(tmp_path, client, episode=1, out="ep1"))
    assert [r.role for r in fake_llm.requests[:3]] == ["causal", "opponent", "tactics"]
    causal = requests_of(fake_llm, "causal")[0].prompt
    assert "Chat: Mined 2 slime_block; Inventory: {'slime_block': 2}" in causal
    assert "Action: mineBlock(bot, 'slime_block', 3)" in causal  # the graph so far
    opp = requests_of(fake_llm, "opponent")[0].prompt
    assert "<Byte> Mined 1 brown_mushroom_block" in opp and "Team blue is clean!" in opp
    assert "<Ryn> Mined" not in opp and "unknown" in opp
    upd = requests_of(fake_llm, "tactics")[0].prompt
    assert "A round has been played" in upd and "<Ryn> Mined 2 slime_block\n<Byte> Mined" in upd  # the chat log
    assert "end of last round:\nRyn: slime_block\nRaze: slime_block\n" in upd  # blocks near the players
    assert "end of last round:\nRyn: slime_block: 2\nRaze: slime_block: 2\n" in upd  # their inventories
    assert "1. Ryn removes slime blocks in the red area." in upd  # previous tactics
    assert "Byte and Blink mine slime blocks" in upd  # opponent tactics
    assert "Examples of good tactics" in upd  # few-shot
    assert team.memory.previous_tactics.startswith("1. Ryn removes") and "3. When the red area" in team.memory.tactics
    assert team.memory.opponent_tactics.startswith("1. Byte and Blink")
    assert any(r.action.startswith("mineBlock(bot, 'slime_block', 2, new Vec3") for r in team.memory.graph.relations)
    rec = record(tmp_path, "ep1")
    assert rec["modules"]["causal"]["merge"] == {"added": 1, "changed": 0, "total": len(GRAPH) + 1}
    assert rec["modules"]["tactics"]["step"] == "update" and rec["modules"]["opponent"]["ok"]


async def test_roles_switches_and_preset(tmp_path, fake_llm, llm_client):
    fake_llm.add(*good_rules())
    team = make_team(
        "tacticrafter",
        "mushroom_war",
        causal=False,
        opponent=False,
        preset_tactics="1. Ryn and Raze mine slime.",
        roles={"action": {"model": "coder", "temperature": 0.0, "max_tokens": 1500}},
    )
    await team.pre_game(context(tmp_path, llm_client()))
    assert {r.role for r in fake_llm.requests} == {"action"}  # no causal, preset tactics
    assert all(
        r.body["model"] == "coder" and r.body["temperature"] == 0.0 and r.body["max_tokens"] == 1500
        for r in fake_llm.requests
    )
    assert "1. Ryn and Raze mine slime." in fake_llm.requests[0].prompt
    ledger = [json.loads(x) for x in (tmp_path / "llm" / "llm_calls.jsonl").read_text().splitlines()]
    assert {x["model"] for x in ledger} == {"coder"}
    played(team)
    fake_llm.reset()
    fake_llm.add(*good_rules())
    await team.pre_game(context(tmp_path, llm_client(), episode=1))
    assert {r.role for r in fake_llm.requests} == {"tactics", "action"}  # updated, still no opponent
    assert "(opponent model disabled)" in requests_of(fake_llm, "tactics")[0].prompt
    assert "(causal model disabled)" in requests_of(fake_llm, "tactics")[0].prompt
    fixed = make_team("tacticrafter", "mushroom_war", preset_tactics="1. Ryn waits.", update_tactics=False)
    played(fixed)
    fake_llm.reset()
    fake_llm.add(*good_rules())
    await fixed.pre_game(context(tmp_path, llm_client()))
    assert fixed.memory.tactics == "1. Ryn waits." and not requests_of(fake_llm, "tactics")
    # the ablation names used by experiment configs
    assert not make_team("tacticrafter", "mushroom_war", enable_causal=False).causal_enabled
    assert not make_team("tacticrafter", "mushroom_war", enable_opponent=False).opponent_enabled


async def test_bad_answers_are_retried_recorded_and_the_team_goes_on(tmp_path, fake_llm, llm_client):
    fake_llm.add(
        Rule(role="causal", reply="Here is the graph: [[broken"),
        Rule(role="tactics", reply="1. Ryn mines slime.\n2. Raze harvests."),
        Rule(role="action", regex="You are Ryn", reply=NO_CODE),
        Rule(role="action", reply=code_answer("async function main(bot) {\n  await craftItem(bot, 'bread', 1)\n}")),
    )
    team = make_team("tacticrafter", "mushroom_war", attempts=2)
    await team.pre_game(context(tmp_path, llm_client()))
    assert len(requests_of(fake_llm, "causal")) == 2 and len(requests_of(fake_llm, "tactics")) == 2
    retry = requests_of(fake_llm, "causal")[1].messages
    assert [m["role"] for m in retry] == ["user", "assistant", "user"] and "no valid JSON" in retry[-1]["content"]
    assert "no [tactics]" in requests_of(fake_llm, "tactics")[1].messages[-1]["content"]
    code_retries = [r.messages[-1]["content"] for r in requests_of(fake_llm, "action") if len(r.messages) > 2]
    assert any("no ```javascript code block" in c for c in code_retries)
    assert any("craftItem" in c and "not available in this scenario" in c for c in code_retries)
    assert len(team.memory.graph) == 0 and team.memory.tactics is None
    assert all(a.program is None for a in team.agents)
    rec = record(tmp_path)
    assert not rec["modules"]["causal"]["ok"] and "no valid JSON" in rec["modules"]["causal"]["error"]
    assert not rec["modules"]["tactics"]["ok"] and rec["llm"]["action"]["unusable"] == 4
    assert "No team tactics" in team.tactics_text()

    # the next episode: good tactics once, then an answer without tags keeps the last good tactics
    fake_llm.reset()
    fake_llm.add(*good_rules())
    await team.pre_game(context(tmp_path, llm_client()))
    assert team.memory.tactics.startswith("1. Ryn removes") and len(team.memory.graph) == len(GRAPH)
    played(team)
    fake_llm.reset()
    fake_llm.add(
        Rule(role="tactics", reply="No tags at all."),
        Rule(role="opponent", reply="I cannot tell."),
        Rule(role="causal", reply='{"oops": 1}'),
        *good_rules(),
    )
    await team.pre_game(context(tmp_path, llm_client(), episode=2))
    assert team.memory.tactics.startswith("1. Ryn removes") and team.memory.tactics_source == "kept"
    assert team.memory.opponent_tactics == "unknown" and len(team.memory.graph) == len(GRAPH)
    assert len(requests_of(fake_llm, "opponent")) == 2


async def test_provider_errors_budget_and_no_client(tmp_path, fake_llm, llm_client):
    fake_llm.add(Rule(role="causal", status=500, message="overloaded"), *good_rules())
    team = make_team("tacticrafter", "mushroom_war")
    await team.pre_game(context(tmp_path, llm_client()))
    rec = record(tmp_path)
    assert "overloaded" in rec["modules"]["causal"]["error"] and len(team.memory.graph) == 0
    assert team.memory.tactics is not None and all(a.program for a in team.agents)  # the rest went on

    # the budget runs out after the causal graph: no action calls, last episode's code is the fallback
    team.memory.code = {"Ryn": {"code": LOOP}}
    fake_llm.reset()
    fake_llm.add(*good_rules())
    client = llm_client("red", "llm.budget.max_calls=1")
    await team.pre_game(context(tmp_path, client))
    assert fake_llm.count == 1 and team.llm_off.startswith("budget")
    rec = record(tmp_path)
    assert rec["llm_off"].startswith("budget") and "BudgetExceeded" in json.dumps(rec["agents"])
    ryn, raze = team.agents
    assert ryn.program is None and ryn.good is not None and ryn.good.entry == "keepFarming" and raze.good is None

    await team.pre_game(context(tmp_path, None))
    assert record(tmp_path)["llm_off"].startswith("no LLM client")


async def test_critic_prompt_and_answers(tmp_path, fake_llm, llm_client):
    from pillagerbench.teams.tacticrafter.base_agent import parse_critique

    fake_llm.add(Rule(role="critic", reply="success!", times=1), Rule(role="critic", reply=CRITIC), *good_rules())
    team = make_team(
        "tacticrafter", "mushroom_war", preset_tactics=TACTICS_1.split("[tactics]")[1].split("[tactics end]")[0]
    )
    ctx = context(tmp_path, llm_client())
    await team.pre_game(ctx)
    ryn = team.agents[0]
    ryn.events = [["onChat", {"onChat": "<Ryn> Mined 1 slime_block"}], ["onError", {"onError": "x"}]]
    ryn.last_error = "Error: No path"
    await ryn.criticize(ctx)
    assert ryn.success is True and ryn.critique.startswith("Keep looping")
    req = requests_of(fake_llm, "critic")[-1]
    assert "Error: No path" in req.prompt and "<Ryn> Mined 1 slime_block" in req.prompt and "Bot: Ryn" in req.prompt
    assert "your JSON" not in req.prompt and "no valid JSON" in req.messages[-1]["content"]
    assert parse_critique('{"success": "false", "critique": null}') == {
        "reasoning": "",
        "success": False,
        "critique": "",
    }
    assert OPPONENT
