"""A person's teammate hears the person (docs/people.md): a person plays Ryn beside a cot teammate (Raze)
on the fake provider, in a real match (a real server, real bots, two short episodes on the real clock),
driven through the page's endpoints as page.html POSTs them; a chat line the person sends in the first
episode is in cot's prompt for the second, in its section for what the team's people said, and in no
prompt before it was said. The prompt section's text itself: tests/teams/test_cot.py."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import httpx

from pillagerbench.llm.fake_server import FakeLLMServer
from pillagerbench.scenarios import make_scenario
from pillagerbench.teams import TeamContext, make_team
from pillagerbench.teams.cot.team import ChainOfThought
from pillagerbench.teams.tacticrafter import TactiCrafter
from pillagerbench.teams.tacticrafter.base_agent import BaseAgent
from tests.support.people import page_url
from tests.support.waiting_cot import ANSWER

EPISODE_S = 10
LINE = "Raze, take the slime off our side first"
SAID = f"<Ryn> {LINE}"
SECTION = "Played by a person, not by your code: Ryn."


def _match(run_dir: Path, fake: FakeLLMServer) -> subprocess.Popen:
    cmd = [sys.executable, "-m", "pillagerbench.cli", "run", "red=cot", "red.humans=[Ryn]", "blue=do_nothing"]
    cmd += ["llm=fake", f"llm.base_url={fake.url}", "llm.max_retries=0", "llm.timeout=10"]
    cmd += [f"episode_length={EPISODE_S}", "episodes=2", f"run_dir={run_dir}", "display=plain"]
    cmd += ["humans.ready_timeout_s=60", "retries=0"]  # two episodes, lagged or not (the checks read both)
    return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=os.environ.copy())


def _state(page: httpx.Client, token: str) -> dict:
    return page.get("state", params={"token": token}).json()


def _play_and_say(page: httpx.Client) -> None:
    """The person takes Ryn, is ready, and once the first episode's game is on sends a chat line."""
    token = page.post("join", json={"name": "alice", "player": "Ryn"}).json()["result"]["token"]
    assert page.post("ready", json={"token": token}).json()["ok"]
    deadline = time.monotonic() + 60
    while not (_state(page, token)["phase"] == "playing" and _state(page, token)["board"].get("episode") == 0):
        assert time.monotonic() < deadline, "the first episode's game never started"
        time.sleep(0.2)
    assert page.post("chat", json={"token": token, "text": LINE}).json()["ok"]
    while not any(c["text"] == SAID for c in _state(page, token)["chat"]):  # the server said it back
        assert time.monotonic() < deadline, "the person's line never came back from the server"
        time.sleep(0.2)


def test_a_cot_teammate_hears_what_the_person_said(tmp_path: Path):
    run_dir = tmp_path / "run"
    with FakeLLMServer(default_reply=ANSWER) as fake:
        proc = _match(run_dir, fake)
        try:
            with httpx.Client(base_url=page_url(proc), timeout=10) as page:
                _play_and_say(page)
            out, _ = proc.communicate(timeout=60)
            assert proc.returncode == 0, out
        finally:
            proc.kill()
        prompts = ["\n".join(str(m.get("content")) for m in r.messages) for r in fake.requests if r.role == "cot"]
    records = [json.loads(line) for line in (run_dir / "episodes.jsonl").read_text().splitlines()]
    assert [r["episode"] for r in records] == [0, 1] and all(r["status"] == "ok" for r in records)
    assert SAID in (run_dir / "episode_000" / "chat.txt").read_text().splitlines()
    assert len(prompts) == 2 and SAID not in prompts[0] and SECTION not in prompts[0]
    assert f"{SECTION} What they said in chat last round, oldest first:\n{SAID}\n" in prompts[1]
    recorded = json.loads((run_dir / "episode_001" / "red" / "cot.json").read_text())["messages"]
    assert recorded[-1]["content"] in prompts[1] and SAID in recorded[-1]["content"]


# --- the prompt's text (no game) ------------------------------------------------------------------

CHAT = ["starting cleanup scenario...", "<Raze> Harvesting red mushrooms", SAID, "<Byte> [Blink signal]"]


def _context(tmp_path: Path, people: tuple[str, ...], chat: list[str]) -> TeamContext:
    sc = make_scenario("mushroom_war")
    return TeamContext(
        scenario=sc,
        side=sc.side("red"),
        players={},
        episode=1,
        out_dir=tmp_path,
        last_episode={"chat": chat},
        people=people,
    )


def _cot_prompt(tmp_path: Path, people: tuple[str, ...], chat: list[str]) -> str:
    return ChainOfThought().messages(_context(tmp_path, people, chat))[-1]["content"]


def _tacticrafter_prompt(tmp_path: Path, people: tuple[str, ...], chat: list[str]) -> str:
    team = make_team("tacticrafter", "mushroom_war")
    assert isinstance(team, TactiCrafter)
    ctx = _context(tmp_path, people, chat)
    team.agents = [BaseAgent(team, name, k) for k, name in enumerate(ctx.side.player_names)]
    return team.agents[1].action_messages(ctx)[-1]["content"]


def test_the_prompt_shows_only_what_the_teams_people_said(tmp_path: Path):
    for prompt in (_cot_prompt, _tacticrafter_prompt):
        alone = prompt(tmp_path, (), CHAT)
        assert alone == prompt(tmp_path, (), []) == prompt(tmp_path, ("Ryn",), CHAT[:2])  # nothing a person said
        assert "Played by a person" not in alone and SAID not in alone
        beside = prompt(tmp_path, ("Ryn",), CHAT)
        assert beside.count(SAID) == 1 and ": Ryn. What they said in chat" in beside
        assert "<Raze> Harvesting" not in beside and "[Blink signal]" not in beside
        assert beside.count("\n") == alone.count("\n") + 4  # a blank line, the heading, the line, the ask
    cot_alone, cot_beside = _cot_prompt(tmp_path, (), CHAT), _cot_prompt(tmp_path, ("Ryn",), CHAT)
    assert cot_alone.endswith("as long as the game lasts.\n") and cot_beside.startswith(cot_alone + "\nPlayed by")
