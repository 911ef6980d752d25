"""The Chain-of-Thought baseline with the fake LLM provider: prompt contents, bad answers and their
fallback, and real episodes on the real server."""

from __future__ import annotations

import asyncio
import json

from pillagerbench.llm.fake_server import Rule
from pillagerbench.players import primitives as prim
from pillagerbench.scenarios import make_scenario
from pillagerbench.teams import TeamContext, make_team
from pillagerbench.teams.cot.team import ChainOfThought
from tests.teams.conftest import play_series

RYN = """\
async function clearSlime(bot, home) {
  if (blockExists(bot, "slime_block", home, 7)) {
    bot.chat("Removing slime from our area")
    await mineBlock(bot, "slime_block", 3, home, 7)
  }
}

async function mainRyn(bot) {
  const home = new Vec3(-9, 4, -10)
  while (true) {
    await clearSlime(bot, home)
    if (blockExists(bot, "red_mushroom_block", home, 7)) await mineBlock(bot, "red_mushroom_block", 4, home, 7)
    await bot.waitForTicks(20)
  }
}"""

RAZE = """\
async function mainRaze(bot) {
  const home = new Vec3(-9, 4, -10)
  while (true) {
    if (blockExists(bot, "red_mushroom_block", home, 7)) {
      bot.chat("Harvesting red mushrooms")
      await mineBlock(bot, "red_mushroom_block", 5, home, 7)
    }
    await bot.waitForTicks(20)
  }
}"""


def answer(*blocks: str) -> str:
    code = "\n".join(f"Code for bot {i}:\n```javascript\n{b}\n```" for i, b in enumerate(blocks))
    return (
        "Explain: first round, nothing to learn from yet.\n"
        "Plan: Ryn clears slime so the mushrooms regrow, then harvests; Raze harvests red mushrooms.\n" + code
    )


SYNTAX_ERROR = "async function main(bot) {\n  await mineBlock(bot, 'red_mushroom_block', 3\n}"
WRONG_PRIMITIVE = "async function main(bot) {\n  await craftItem(bot, 'bread', 1)\n}"


def context(tmp_path, llm, last_episode=None, observations=None) -> TeamContext:
    sc = make_scenario("mushroom_war")
    side = sc.side("red")
    return TeamContext(
        scenario=sc,
        side=side,
        players={},
        episode=0,
        out_dir=tmp_path / "red",
        observations=observations or {},
        last_episode=last_episode or {},
        llm=llm,
    )


async def test_prompt_holds_everything_the_paper_lists(tmp_path, fake_llm, llm_client):
    fake_llm.add(Rule(role="cot", reply=answer(RYN, RAZE)))
    team = make_team("cot", "mushroom_war")
    obs = {
        "Ryn": [
            [
                "observe",
                {
                    "voxels": ["slime_block", "red_mushroom_block"],
                    "status": {"position": {"x": -7.5, "y": 4, "z": -9.5}, "entities": {"cow": 4.0}},
                },
            ]
        ]
    }
    await team.pre_game(context(tmp_path, llm_client(), observations=obs))
    assert fake_llm.count == 1
    req = fake_llm.requests[-1]
    system, user = req.messages[0]["content"], req.messages[1]["content"]
    assert prim.doc("mineBlock") in system and prim.doc("mineflayer") in system
    assert prim.doc("craftItem") not in system  # not a Mushroom War primitive
    assert "Code for Ryn:" in system and "Code for Raze:" in system
    sc = make_scenario("mushroom_war")
    assert sc.description() in user
    assert "Team name: red_team" in user and "Team players: Ryn, Raze" in user
    assert "Ryn (at x=-7.5, y=4, z=-9.5): red_mushroom_block, slime_block" in user
    assert "cow (4 blocks away)" in user
    assert "No code yet" in user
    rec = json.loads((tmp_path / "red" / "cot.json").read_text())
    assert rec["status"] == "ok" and set(rec["programs"]) == {"Ryn", "Raze"}
    assert rec["programs"]["Ryn"]["entry"] == "mainRyn" and rec["messages"][1]["content"] == user


async def test_last_episode_code_errors_and_chat_reach_the_next_prompt(tmp_path, fake_llm, llm_client):
    fake_llm.add(Rule(role="cot", reply=answer(RYN, SYNTAX_ERROR)))
    team = make_team("cot", "mushroom_war", attempts=1)
    client = llm_client()
    await team.pre_game(context(tmp_path, client))
    events_dir = tmp_path / "events"
    events_dir.mkdir()
    lines = [["onChat", {"onChat": "<Ryn> Removing slime"}]] * 3 + [
        ["onChat", {"onChat": "Team red is clean!"}],
        ["onError", {"onError": "Error: No path\nat line 3: x"}],
        ["observe", {}],
    ]
    (events_dir / "Ryn.jsonl").write_text("\n".join(json.dumps(e) for e in lines))
    await team.pre_game(context(tmp_path, client, last_episode={"events_dir": str(events_dir)}))
    user = fake_llm.requests[-1].messages[1]["content"]
    assert "Ryn:\n```javascript\n" + RYN in user  # last round's code
    assert "Your code was not used: Raze: the code does not parse" in user
    assert "Error: No path" in user
    assert user.count("<Ryn> Removing slime") == 1 and "Team red is clean!" in user
    assert team.state()["last_code"]["Raze"] == SYNTAX_ERROR
    fresh = ChainOfThought()
    fresh.load_state(json.loads(json.dumps(team.state())))
    assert fresh.last_code == team.last_code and fresh.last_problems == team.last_problems


async def test_bad_answers_are_retried_with_the_problems_then_recorded(tmp_path, fake_llm, llm_client):
    fake_llm.add(
        Rule(role="cot", reply="Explain: hmm.\nPlan: we will see.", times=1),
        Rule(role="cot", reply=answer(RYN), times=1),
        Rule(role="cot", reply=answer(RYN, WRONG_PRIMITIVE)),
    )
    team = make_team("cot", "mushroom_war", attempts=3)
    await team.pre_game(context(tmp_path, llm_client()))
    assert fake_llm.count == 3
    retry = fake_llm.requests[1].messages
    assert [m["role"] for m in retry] == ["system", "user", "assistant", "user"]
    assert "no ```javascript code block" in retry[-1]["content"]
    assert "Raze: no code block" in fake_llm.requests[2].messages[-1]["content"]
    rec = json.loads((tmp_path / "red" / "cot.json").read_text())
    assert rec["status"] == "partial" and len(rec["attempts"]) == 3
    assert set(rec["programs"]) == {"Ryn"}
    assert "craftItem" in rec["failures"]["Raze"] and "not available in this scenario" in rec["failures"]["Raze"]
    assert team.programs[0] is not None and team.programs[1] is None


async def test_a_good_retry_ends_the_attempts(tmp_path, fake_llm, llm_client):
    fake_llm.add(Rule(role="cot", reply=answer(SYNTAX_ERROR, RAZE), times=1), Rule(role="cot", reply=answer(RYN, RAZE)))
    team = make_team("cot", "mushroom_war", attempts=5)
    await team.pre_game(context(tmp_path, llm_client()))
    assert fake_llm.count == 2 and all(team.programs)
    assert "Ryn: the code does not parse: SyntaxError" in fake_llm.requests[1].messages[-1]["content"]


async def test_provider_errors_and_budgets_fail_the_episode_not_the_team(tmp_path, fake_llm, llm_client):
    fake_llm.add(Rule(role="cot", status=500, message="overloaded"))
    team = make_team("cot", "mushroom_war")
    await team.pre_game(context(tmp_path, llm_client()))
    rec = json.loads((tmp_path / "red" / "cot.json").read_text())
    assert rec["status"] == "failed" and "overloaded" in rec["error"] and team.programs == [None, None]
    assert "overloaded" in rec["failures"]["Ryn"]

    fake_llm.reset()
    fake_llm.add(Rule(role="cot", reply=answer(RYN, RAZE)))
    client = llm_client("red", "llm.budget.max_calls=0")
    await team.pre_game(context(tmp_path, client))
    rec = json.loads((tmp_path / "red" / "cot.json").read_text())
    assert rec["status"] == "failed" and "BudgetExceeded" in rec["error"] and fake_llm.count == 0

    await team.pre_game(context(tmp_path, None))
    assert json.loads((tmp_path / "red" / "cot.json").read_text())["error"].startswith("no LLM client")


async def test_cot_episodes_on_the_real_server(tmp_path, fake_llm, llm_client):
    """Two matches at once: (1) the scripted answer mines slime and harvests mushrooms and scores;
    (2) a series whose first answer has no code (both players idle) and whose second has a syntax
    error for Raze (Ryn plays, Raze idles) goes on. On the lockstep clock: what the team does with its
    answers, not game time (which a loaded machine's lag would shrink), and faster than real time."""
    fake_llm.add(
        Rule(role="cot", regex=r"Your code was not used", reply=answer(RYN, SYNTAX_ERROR)),
        Rule(role="cot", model="scorer", reply=answer(RYN, RAZE)),
        Rule(role="cot", reply="Explain: no idea.\nPlan: none."),
    )
    good, series = llm_client("red", "llm.model=scorer"), llm_client("red")
    scoring, fallback = await asyncio.gather(
        play_series(
            "mushroom_war",
            make_team("cot", "mushroom_war"),
            "do_nothing",
            tmp_path / "good",
            length=30,
            llms={"red": good},
            clock="lockstep",
        ),
        play_series(
            "mushroom_war",
            make_team("cot", "mushroom_war", attempts=2),
            "do_nothing",
            tmp_path / "series",
            episodes=2,
            length=12,
            llms={"red": series},
            clock="lockstep",
        ),
    )

    (rec,) = scoring
    assert rec.status == "ok", rec.error
    # a red mushroom block drops a mushroom with p = 2/9 (vanilla's loot table), so a slow machine's few
    # digs may score 0: the test asks for the digs, and for a score that is the mushrooms picked up
    world = [json.loads(line) for line in (tmp_path / "good" / "episode_000" / "world_events.jsonl").open()]
    red = ("Ryn", "Raze")
    dug = [e for e in world if e["event"] == "block_dug" and e["player"] in red]
    assert {e["block"] for e in dug} == {"slime_block", "red_mushroom_block"}, (dug, rec.bot_lag)
    picked = sum(
        e["count"]
        for e in world
        if e["event"] == "item_picked_up" and e["item"] == "red_mushroom" and e["player"] in red
    )
    assert rec.red_score == picked and rec.blue_score == 0
    ryn, raze = rec.iterations["red"]
    assert ryn >= 1 and raze >= 1
    cot = json.loads((tmp_path / "good" / "episode_000" / "red" / "cot.json").read_text())
    assert cot["status"] == "ok" and cot["iterations"] == {"Ryn": ryn, "Raze": raze}
    events = [json.loads(line) for line in (tmp_path / "good" / "episode_000" / "events" / "Ryn.jsonl").open()]
    chats = [e[1]["onChat"] for e in events if e[0] == "onChat"]
    assert any(c.startswith("<Ryn> Mined") and "slime_block" in c for c in chats), chats[:20]

    first, second = fallback
    assert first.status == "ok" and second.status == "ok", (first.error, second.error)
    assert first.red_score == 0 and first.iterations["red"] == [0, 0]
    c0 = json.loads((tmp_path / "series" / "episode_000" / "red" / "cot.json").read_text())
    assert c0["status"] == "failed" and len(c0["attempts"]) == 2
    assert "no ```javascript code block" in c0["failures"]["Ryn"]
    c1 = json.loads((tmp_path / "series" / "episode_001" / "red" / "cot.json").read_text())
    assert c1["status"] == "partial" and set(c1["programs"]) == {"Ryn"}
    assert "does not parse" in c1["failures"]["Raze"]
    assert second.iterations["red"][0] >= 1 and second.iterations["red"][1] == 0


ONCE = "async function main{name}(bot) {{\n  bot.chat('{name} was here')\n}}"


async def test_upstream_protocol_asks_once(tmp_path, fake_llm, llm_client):
    fake_llm.add(Rule(role="cot", reply="Explain: hmm.\nPlan: we will see."))
    team = make_team("cot", "mushroom_war", attempts=3)
    ctx = context(tmp_path, llm_client())
    ctx.protocol = "upstream"
    await team.pre_game(ctx)
    assert fake_llm.count == 1 and team.programs == [None, None]  # never sent back (ours: 3 calls)
    rec = json.loads((tmp_path / "red" / "cot.json").read_text())
    assert rec["protocol"] == "upstream" and len(rec["attempts"]) == 1


async def test_upstream_protocol_runs_a_program_at_most_10_times(tmp_path, fake_llm, llm_client):
    """Programs that end at once: upstream's loop starts them 10 times, ours until the whistle (the
    cap alone: with upstream's 8 s of step waits, ten runs would need an 80 s episode; next test)."""
    fake_llm.add(Rule(role="cot", reply=answer(ONCE.format(name="Ryn"), ONCE.format(name="Raze"))))
    team = make_team("cot", "mushroom_war", restart_pause_s=0.2)
    (rec,) = await play_series(
        "mushroom_war",
        team,
        "do_nothing",
        tmp_path,
        length=12,
        llms={"red": llm_client("red")},
        protocol="upstream",
        step_wait_s=0.0,
    )
    assert rec.status == "ok", rec.error
    assert rec.protocol == "upstream" and rec.iterations["red"] == [10, 10]
    assert rec.runs == {"Ryn": 10, "Raze": 10}


async def test_upstream_protocol_waits_4_s_before_and_after_every_run(tmp_path, fake_llm, llm_client):
    """Upstream's /step waited 80 ticks before the code and 80 after: a program that ends at once
    starts at 4 s and again only at about 12.2 s, after a 12 s whistle (ours: dozens of runs)."""
    fake_llm.add(Rule(role="cot", reply=answer(ONCE.format(name="Ryn"), ONCE.format(name="Raze"))))
    team = make_team("cot", "mushroom_war", restart_pause_s=0.2)
    (rec,) = await play_series(
        "mushroom_war", team, "do_nothing", tmp_path, length=12, llms={"red": llm_client("red")}, protocol="upstream"
    )
    assert rec.status == "ok", rec.error
    assert rec.runs == {"Ryn": 1, "Raze": 1}


EMPTY_MAIN = "async function main(bot) {\n}"  # the answer format's empty main, copied as it is


async def test_code_that_does_nothing_is_asked_again_under_our_protocol_not_upstreams(tmp_path, fake_llm, llm_client):
    fake_llm.add(Rule(role="cot", reply=answer(EMPTY_MAIN, RAZE), times=1), Rule(role="cot", reply=answer(RYN, RAZE)))
    team = make_team("cot", "mushroom_war", attempts=3)
    await team.pre_game(context(tmp_path, llm_client()))
    assert fake_llm.count == 2 and all(team.programs)
    assert "Ryn: the code does nothing: `main` calls no function at all" in fake_llm.requests[1].messages[-1]["content"]
    fake_llm.reset()
    fake_llm.add(Rule(role="cot", reply=answer(EMPTY_MAIN, RAZE)))
    upstream = make_team("cot", "mushroom_war", attempts=3)
    ctx = context(tmp_path / "upstream", llm_client())
    ctx.protocol = "upstream"
    await upstream.pre_game(ctx)
    assert fake_llm.count == 1 and all(upstream.programs)  # upstream's took any code


class DeadBot:
    """A player handle whose bot is gone for good: every run fails before it starts, without awaiting."""

    name = "Ryn"

    async def run(self, code, *, timeout=None, on_event=None):
        raise RuntimeError("Ryn: the bot is not running (call start())")

    async def stop(self):
        return None

    async def observe(self):
        return []


async def test_a_bot_dead_for_good_with_no_restart_pause_does_not_spin(tmp_path, fake_llm, llm_client):
    fake_llm.add(Rule(role="cot", reply=answer(RYN, RAZE)))
    team = make_team("cot", "mushroom_war", restart_pause_s=0.0)
    ctx = context(tmp_path, llm_client())
    await team.pre_game(ctx)
    ctx.deadline = ctx.clock.now() + 0.5
    team.iterations = [0, 0]
    other = asyncio.create_task(asyncio.sleep(0.1))  # the event loop's other tasks still run
    await asyncio.wait_for(team._keep_running(ctx, 0, DeadBot()), 5)
    assert other.done() and 1 <= team.iterations[0] <= 0.5 / 0.05 + 2, team.iterations


async def test_a_remote_teams_bot_dead_for_good_with_no_restart_pause_does_not_spin(tmp_path):
    """The remote team's loop restarts its player's program as cot's does (TeamContext.pause_before_rerun):
    with restart_pause_s=0 a run that fails before it starts waits a tick, never a loop that does not yield."""
    team = make_team("remote", "mushroom_war", url="http://127.0.0.1:9", restart_pause_s=0.0)
    ctx = context(tmp_path, None)
    ctx.deadline = ctx.clock.now() + 0.5
    team.programs, team.versions, team.iterations, team.problems = {"Ryn": "await bot.chat('hi')"}, {"Ryn": 1}, [0], []
    ctx.players = {"Ryn": DeadBot()}
    other = asyncio.create_task(asyncio.sleep(0.1))
    await asyncio.wait_for(team._keep_running(ctx, 0, "Ryn", {"Ryn": []}), 5)
    assert other.done() and 1 <= team.iterations[0] <= 0.5 / 0.05 + 2, team.iterations
    assert team.problems[0] == "Ryn: RuntimeError: Ryn: the bot is not running (call start())", team.problems
