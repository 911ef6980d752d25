"""The `tools` team (teams/tools/llm_team.py) on the real server and the lockstep clock, its model the fake
provider scripted to answer with tool calls: (1) each player mines red mushroom blocks, one call each per
answer, then the model only asks for the status until max_turns: the team scores, the requests carry the
scenario's tools and the results of the last turn's calls, the conversation stays bounded, tools.jsonl
lists the calls; in the next episode (the same seat) the players wait, the whistle ending a turn; (2) bad answers (arguments not JSON, an unknown tool, a player of the other team, bad
arguments, an answer without a call, then a provider error) are tool errors and problems, and the
episode completes, its thinking charged in game time (clock.ticks_per_1k_tokens) as its players waiting.
Both series play at once (two servers)."""

from __future__ import annotations

import asyncio
import json

from pillagerbench.config.schema import ClockConfig
from pillagerbench.llm.fake_server import Rule
from pillagerbench.scenarios import make_scenario
from pillagerbench.teams import make_team
from pillagerbench.teams.tools import tools_of
from pillagerbench.teams.tools.llm_team import DROPPED, NUDGE

MINE = {"name": "red_mushroom_block", "count": 2, "point": [-9, 4, -10], "maxDistance": 7}
GIANTS = {"Ryn": [-13, 5, -8], "Raze": [-5, 5, -8]}  # each player its own giant mushroom first
WAIT = lambda player: {"name": "wait", "arguments": {"player": player, "ticks": 150}}  # noqa: E731
TURN = [{"name": "mineBlock", "arguments": {"player": p, **MINE, "point": at}} for p, at in GIANTS.items()]
BAD = [
    {"name": "mineBlock", "arguments": '{"player": "Ryn", "name": '},  # not JSON
    {"name": "fly", "arguments": {"player": "Ryn"}},  # no such tool
    {"name": "mineBlock", "arguments": {"player": "Byte", "name": "red_mushroom_block"}},  # blue's player
    {"name": "mineBlock", "arguments": {"player": "Raze", "name": "red_mushroom_block", "count": "two"}},
]


def script(fake_llm) -> None:
    fake_llm.add(
        Rule(model="good", match="Episode 1 is about", tool_calls=[WAIT("Ryn"), WAIT("Raze")]),
        Rule(model="good", tool_calls=TURN, times=4),
        Rule(model="good", tool_calls=[{"name": "status"}]),
        Rule(model="bad", tool_calls=BAD, times=1),
        Rule(model="bad", reply="Let me think about the plan first.", times=1),
        Rule(model="bad", tool_calls=[{"name": "mineBlock", "arguments": {"player": "Ryn", **MINE}}], times=2),
        Rule(model="bad", status=500, message="overloaded"),
    )


def requests_of(fake_llm, model: str) -> list:
    return [r for r in fake_llm.requests if r.body.get("model") == model]


def calls_of(run_dir, episode: int = 0) -> list[dict]:
    return [json.loads(line) for line in (run_dir / f"episode_{episode:03d}" / "red" / "tools.jsonl").open()]


async def test_the_tools_team_plays_through_function_calls(tmp_path, fake_llm, llm_client):
    from tests.teams.conftest import play_series

    script(fake_llm)
    good = make_team("tools", "mushroom_war", max_turns=10, history_turns=3)
    bad = make_team("tools", "mushroom_war")
    (scored, waited), (failed,) = await asyncio.gather(
        play_series(
            "mushroom_war",
            good,
            "do_nothing",
            tmp_path / "good",
            episodes=2,
            length=20,
            llms={"red": llm_client("red", "llm.model=good")},
            clock="lockstep",
            seed=3,
        ),
        play_series(
            "mushroom_war",
            bad,
            "do_nothing",
            tmp_path / "bad",
            length=15,
            llms={"red": llm_client("red", "llm.model=bad")},
            clock=ClockConfig(mode="lockstep", speed="max", ticks_per_1k_tokens=1000),  # thinking costs game time
        ),
    )
    good_requests = requests_of(fake_llm, "good")
    check_scoring(tmp_path / "good", scored, good_requests[:10])
    check_next_episode(tmp_path / "good", waited, good_requests[10:], scored.red_score)
    check_bad_answers(tmp_path / "bad", failed, requests_of(fake_llm, "bad"))


def check_scoring(run_dir, rec, requests) -> None:
    assert rec.status == "ok", rec.error
    assert rec.red_score > 0 and rec.blue_score == 0, (rec.red_score, rec.iterations)
    first = requests[0]
    assert first.role == "action" and first.messages[0]["role"] == "system" and "Mushroom War" in first.prompt
    assert [t["function"]["name"] for t in first.tools] == [
        t.name for t in tools_of(make_scenario("mushroom_war"), "red")
    ]
    system, user, answer, *results = requests[1].messages
    assert answer["role"] == "assistant" and [r["role"] for r in results] == ["tool", "tool"]
    assert [r["tool_call_id"] for r in results] == [c["id"] for c in answer["tool_calls"]]
    assert [json.loads(r["content"])["player"] for r in results] == ["Ryn", "Raze"]
    assert "observation" in json.loads(results[0]["content"]) and "Episode 0" in user["content"]
    later = requests[4].messages  # history_turns=3: the opening and the last three turns, older observations dropped
    assert len(later) == 2 + 3 * 3 and later[2] == requests[2].messages[5]  # turn 2: the answer to request 1
    assert json.loads(later[3]["content"])["observation"] == DROPPED
    assert json.loads(later[-1]["content"])["observation"] != DROPPED
    calls = calls_of(run_dir)
    assert calls[0]["clock"] == "lockstep"
    mined = [c for c in calls[1:] if c["tool"] == "mineBlock"]
    assert len(mined) >= 4 and all("tick_start" in c and "refused" not in c for c in mined)
    assert mined[0]["tick_start"] == mined[1]["tick_start"] == 0  # one answer's calls start on one tick
    # the world waits while the model thinks: a turn starts on the tick its last one ended
    assert mined[2]["tick_start"] == mined[3]["tick_start"] == max(mined[0]["tick_end"], mined[1]["tick_end"])
    acted = [c["arguments"]["player"] for c in mined]
    assert rec.iterations["red"] == [acted.count("Ryn"), acted.count("Raze")]
    assert len(requests) == 10 and "max_turns=10 LLM calls made: no more turns this episode" in rec.problems["red"]
    assert "the agent left: its players did nothing for the rest of the episode" in rec.problems["red"]
    transcript = json.loads((run_dir / "episode_000" / "red" / "transcript.json").read_text())
    assert len(transcript["asks"]) == 10 and transcript["messages"][:2] == first.messages


def check_bad_answers(run_dir, rec, requests) -> None:
    assert rec.status == "ok", rec.error
    assert rec.red_score == 0 or rec.red_score > 0  # played to the whistle: whatever Ryn's one call got
    errors = [m["content"] for m in requests[1].messages if m["role"] == "tool"]
    assert len(errors) == 4 and all(e.startswith("error: ") for e in errors), errors
    assert "the arguments are not a JSON object" in errors[0]
    assert "unknown tool 'fly'" in errors[1]
    assert "player 'Byte' is not on the red team" in errors[2]
    assert "bad arguments: count: 'two' is not of type 'integer'" in errors[3]
    assert requests[2].messages[-1] == {"role": "user", "content": NUDGE}
    assert rec.iterations["red"] == [2, 0]
    problems = rec.problems["red"]
    assert any(p.startswith("LLM: ProviderError: HTTP 500: overloaded") for p in problems), problems
    assert any(p.startswith("4 tool call(s) refused or malformed") for p in problems), problems
    calls = calls_of(run_dir)[1:]
    assert [c["tool"] for c in calls] == [
        "fly",
        "mineBlock",
        "mineBlock",
        "mineBlock",
        "mineBlock",
    ]  # not the malformed
    first, second = calls[-2:]  # thinking between them charged (clock.ticks_per_1k_tokens), the world running
    assert second["tick_start"] > first["tick_end"], (first, second)


def check_next_episode(run_dir, rec, requests, last_score: float) -> None:
    """Episode 1 in the same seat: a new conversation that knows the last score; waits until the whistle ends one."""
    assert rec.status == "ok" and not rec.problems.get("red"), (rec.error, rec.problems)
    assert (
        2 <= len(requests) <= 4
        and f"Last episode: your team {last_score:g} points, the opponents 0." in requests[0].prompt
    )
    waits = calls_of(run_dir, 1)[1:]
    assert {c["tool"] for c in waits} == {"wait"} and rec.iterations["red"] == [len(waits) // 2] * 2
    assert waits[-1]["tick_end"] == 400  # the whistle (20 s) ended the last turn
    transcript = json.loads((run_dir / "episode_001" / "red" / "transcript.json").read_text())
    assert transcript["stopped"] == "the whistle" and transcript["episode"] == 1
