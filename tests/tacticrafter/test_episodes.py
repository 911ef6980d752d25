"""TactiCrafter on the real server with the fake LLM provider: a two-episode series that learns
(tactics, graph and opponent model generated, then updated from the first episode's events), its
checkpoint round trip, and a series full of bad inputs that keeps playing."""

from __future__ import annotations

import json

from pillagerbench.llm.fake_server import Rule
from pillagerbench.teams import make_team
from pillagerbench.teams.tacticrafter import TactiCrafter

from .conftest import (
    CRITIC,
    GRAPH,
    LOOP,
    NO_CODE,
    ONE_PASS,
    OPPONENT,
    TACTICS_1,
    THROWS,
    code_answer,
    context,
    good_rules,
    play_series,
    requests_of,
)


def load(path):
    return json.loads(path.read_text())


async def test_two_episode_series_learns_and_checkpoints(tmp_path, fake_llm, llm_client):
    fake_llm.add(*good_rules())
    team = make_team("tacticrafter", "mushroom_war", iterations=4)
    run = tmp_path / "series"
    # on the lockstep clock: what the team learns and keeps, not game time (the two tests below, with
    # their wall-clock LLM timeouts and upstream's protocol, play on the real clock)
    first, second = await play_series(
        team, "passive", run, episodes=2, length=20, llms={"red": llm_client()}, clock="lockstep"
    )
    assert first.status == "ok" and second.status == "ok", (first.error, second.error)

    # episode 0: graph and tactics generated, opponent unknown, code iterated in the game
    ep0 = run / "episode_000" / "red"
    assert load(ep0 / "tactics.json")["source"] == "generated"
    assert load(ep0 / "opponent_tactics.json")["opponent_tactics"] == "unknown"
    assert len(load(ep0 / "causal_graph.json")["relations"]) == 6
    rec0 = load(ep0 / "tacticrafter.json")
    ryn0, raze0 = first.iterations["red"]
    assert 2 <= ryn0 <= 4 and 2 <= raze0 <= 4  # one pass, critique, new code, ...
    assert rec0["iterations"] == {"Ryn": ryn0, "Raze": raze0}
    its = rec0["agents"]["Ryn"]["iterations"]
    assert its[0]["entry"] == "onePass" and its[1]["entry"] == "keepFarming" and its[0]["success"] is True
    assert rec0["llm"]["critic"]["calls"] >= 2 and rec0["llm"]["action"]["calls"] >= 4
    assert rec0["dedup"]["total"]["events_before"] >= rec0["dedup"]["total"]["events_after"] > 0
    code0 = load(ep0 / "code.json")
    assert code0["Ryn"]["code"] == LOOP and code0["Ryn"]["iterations"] == ryn0
    assert any(e[0] == "onChat" for e in code0["Ryn"]["events"])
    # the code acted in the game: the server saw red's players dig the slime of their area
    world = [json.loads(line) for line in (run / "episode_000" / "world_events.jsonl").read_text().splitlines()]
    dug = [e for e in world if e["event"] == "block_dug" and e["block"] == "slime_block"]
    assert {e["player"] for e in dug} & {"Ryn", "Raze"}, dug
    assert first.red_score == load(run / "episode_000" / "timeline.json")[-1]["red"]

    # episode 1: everything updated from episode 0's events
    ep1 = run / "episode_001" / "red"
    t1 = load(ep1 / "tactics.json")
    assert t1["source"] == "updated" and t1["previous_tactics"] == load(ep0 / "tactics.json")["tactics"]
    assert load(ep1 / "opponent_tactics.json")["opponent_tactics"].startswith("1. Byte and Blink")
    assert len(load(ep1 / "causal_graph.json")["relations"]) == 7
    causal_update = [r for r in requests_of(fake_llm, "causal") if "The causal graph so far" in r.prompt]
    assert len(causal_update) == 1
    assert "Chat: Clearing slime once; Inventory:" in causal_update[0].prompt
    opp = requests_of(fake_llm, "opponent")
    assert len(opp) == 1 and ("<Byte> Mined" in opp[0].prompt or "<Blink> Mined" in opp[0].prompt)
    upd = [r for r in requests_of(fake_llm, "tactics") if "A round has been played" in r.prompt]
    assert len(upd) == 1 and "<Ryn> Clearing slime once" in upd[0].prompt
    first_code_ep1 = [
        r
        for r in requests_of(fake_llm, "action")
        if "keepFarming" in r.prompt and "3. When the red area is clean" in r.prompt
    ]
    assert first_code_ep1  # last episode's code and new tactics
    assert second.iterations["red"][0] >= 1

    # checkpoint round trip, and a team that starts from it continues (update, not a fresh start)
    ckpt = tmp_path / "ckpt"
    team.save_checkpoint(ckpt)
    assert {p.name for p in ckpt.iterdir()} >= {
        "team.json",
        "tactics.json",
        "opponent_tactics.json",
        "causal_graph.json",
        "code.json",
    }
    again = make_team("tacticrafter", "mushroom_war", checkpoint=str(ckpt))
    assert again.state() == json.loads(json.dumps(team.state()))
    from_dir = TactiCrafter(checkpoint=str(ep1))  # an episode's directory works as well
    assert (
        from_dir.memory.tactics == team.memory.tactics
        and from_dir.memory.graph.relations == team.memory.graph.relations
    )
    assert from_dir.memory.code["Ryn"]["code"] == team.memory.code["Ryn"]["code"]
    fake_llm.reset()
    fake_llm.add(*good_rules())
    await again.pre_game(context(tmp_path, llm_client(), episode=5, out="resumed"))
    assert [r.role for r in fake_llm.requests[:3]] == ["causal", "opponent", "tactics"]
    assert "A round has been played" in requests_of(fake_llm, "tactics")[0].prompt
    assert load(tmp_path / "resumed" / "tactics.json")["previous_tactics"] == team.memory.tactics


async def test_bad_inputs_in_the_game_keep_the_team_playing(tmp_path, fake_llm, llm_client):
    """Ryn: no code in the pre-game, then code that throws at once, then good code. Raze: good
    one-pass code, then its next code request times out (the last good code runs again). Tactics
    without tags and an invalid graph: the team plays without them."""
    fake_llm.add(
        Rule(role="causal", reply="no graph today"),
        Rule(role="tactics", reply="Just mine stuff."),
        Rule(role="critic", regex="Bot: Ryn", reply="not json"),
        Rule(role="critic", reply=CRITIC),
        Rule(role="action", regex="You are Ryn", match="No code yet.", reply=NO_CODE, times=2),
        Rule(role="action", regex="You are Ryn", match="No code yet.", reply=code_answer(THROWS)),
        Rule(role="action", regex="You are Ryn", reply=code_answer(LOOP)),
        Rule(role="action", regex="You are Raze", match="No code yet.", reply=code_answer(ONE_PASS)),
        Rule(role="action", regex="You are Raze", delay=3.0),
    )
    team = make_team("tacticrafter", "mushroom_war", attempts=2, min_llm_time_s=2.0)
    client = llm_client("red", "llm.timeout=1", "llm.max_retries=0")
    (rec,) = await play_series(team, "do_nothing", tmp_path / "bad", length=22, llms={"red": client})
    assert rec.status == "ok", rec.error
    out = load(tmp_path / "bad" / "episode_000" / "red" / "tacticrafter.json")
    assert not out["modules"]["causal"]["ok"] and not out["modules"]["tactics"]["ok"]
    assert load(tmp_path / "bad" / "episode_000" / "red" / "tactics.json")["tactics"] is None

    ryn = out["agents"]["Ryn"]
    pre = ryn["calls"][0]
    assert pre["role"] == "action" and not pre["ok"] and "no ```javascript code block" in pre["error"]
    its = ryn["iterations"]
    assert its[0]["entry"] == "main" and its[0]["failed_at_once"] and "boom at once" in its[0]["errors"][0]
    assert any(i["entry"] == "keepFarming" for i in its[1:])
    critic_calls = [c for c in ryn["calls"] if c["role"] == "critic"]
    assert critic_calls and not critic_calls[0]["ok"] and "no valid JSON" in critic_calls[0]["error"]

    raze = out["agents"]["Raze"]
    timeouts = [c for c in raze["calls"] if c["role"] == "action" and not c["ok"]]
    assert timeouts and "LLMTimeout" in timeouts[0]["error"]
    assert len(raze["iterations"]) >= 2 and all(i["entry"] == "onePass" for i in raze["iterations"])
    assert rec.iterations["red"][1] == len([i for i in raze["iterations"] if i["counted"]])
    assert out["llm"]["action"]["failed_calls"] >= 1
    code = load(tmp_path / "bad" / "episode_000" / "red" / "code.json")
    assert code["Ryn"]["code"] == LOOP and code["Raze"]["code"] == ONE_PASS


async def test_upstream_protocol_neither_reruns_nor_asks_again(tmp_path, fake_llm, llm_client):
    """Cap of 2 iterations. Ryn: one-pass code, then an answer without code: upstream's loop spends
    an iteration on it (no run, no re-ask, no fallback to the last good code), then idles. Raze:
    one-pass code twice, then idles (ours would run it again after the cap)."""
    fake_llm.add(
        Rule(role="causal", reply=json.dumps(GRAPH)),
        Rule(role="opponent", reply=OPPONENT),
        Rule(role="tactics", reply=TACTICS_1),
        Rule(role="critic", reply=CRITIC),
        Rule(role="action", regex="You are Ryn", match="No code yet.", reply=code_answer(ONE_PASS)),
        Rule(role="action", regex="You are Ryn", reply=NO_CODE),
        Rule(role="action", regex="You are Raze", reply=code_answer(ONE_PASS)),
    )
    team = make_team("tacticrafter", "mushroom_war", iterations=2, attempts=3)
    (rec,) = await play_series(
        team, "do_nothing", tmp_path, length=25, llms={"red": llm_client("red")}, protocol="upstream"
    )
    assert rec.status == "ok", rec.error
    out = load(tmp_path / "episode_000" / "red" / "tacticrafter.json")
    assert out["protocol"] == "upstream"
    ryn, raze = out["agents"]["Ryn"], out["agents"]["Raze"]
    assert [i.get("entry") for i in ryn["iterations"]] == ["onePass", None] and ryn["iterations"][1]["no_code"]
    ryn_actions = [c for c in ryn["calls"] if c["role"] == "action"]
    assert len(ryn_actions) == 2 and len(ryn_actions[1]["attempts"]) == 1  # ours: 3 attempts
    assert [i["entry"] for i in raze["iterations"]] == ["onePass", "onePass"]
    assert ryn["reruns"] == raze["reruns"] == 0 and "idle_from_s" in raze
    assert rec.iterations["red"] == [2, 2] and rec.runs == {"Ryn": 1, "Raze": 2}
