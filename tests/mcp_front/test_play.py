"""`pillagerbench mcp` on the real server, played by a scripted agent on the official SDK's own client
(stdio and streamable HTTP), on the lockstep clock: it plays and outscores do_nothing, `report` reads its
run, the same seed gives the same game however long the agent pauses between calls, bad calls are tool
errors and the game goes on, a client that leaves ends the run cleanly, a bad key is one line."""

from __future__ import annotations

import asyncio
import json
import os
import random
import subprocess
import sys
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from pathlib import Path
from typing import Any

from mcp import ClientSession, StdioServerParameters
from mcp.client.stdio import stdio_client
from mcp.client.streamable_http import streamable_http_client
from mcp.types import CallToolResult, Implementation, TextContent

from tests.support.cli import run_cli

MCP = [sys.executable, "-m", "pillagerbench.cli", "mcp"]
LOCKSTEP = ("clock=lockstep", "episode_length=10")
ME = Implementation(name="scripted", version="1.0")


def _env() -> dict[str, str]:
    return {k: v for k, v in os.environ.items() if k != "OPENAI_API_KEY"}


@asynccontextmanager
async def stdio_session(cwd: Path, *keys: str) -> AsyncIterator[ClientSession]:
    params = StdioServerParameters(command=MCP[0], args=[*MCP[1:], *keys], cwd=str(cwd), env=_env())
    with open(cwd / "mcp.stderr", "a") as errlog:
        async with stdio_client(params, errlog=errlog) as (read, write):
            async with ClientSession(read, write, client_info=ME) as session:
                await session.initialize()
                yield session


async def call(session: ClientSession, name: str, arguments: dict[str, Any]) -> tuple[bool, str]:
    result = await session.call_tool(name, arguments)
    assert isinstance(result, CallToolResult) and isinstance(result.content[0], TextContent)
    return bool(result.is_error), result.content[0].text


async def harvest(
    session: ClientSession, *, pause_s: float = 0.0, seed: int = 0, whistles: list[int] | None = None
) -> int:
    """Each player mines its team's mushrooms, one call at a time, until the run is over; returns the
    number of actions. `pause_s`: a random pause of up to that many seconds before each call; `whistles`:
    the episodes in which a call was in flight at the whistle."""
    rng, actions, whistles = random.Random(seed), 0, [] if whistles is None else whistles
    while True:
        error, text = await call(session, "status", {})
        status = json.loads(text)
        if status["phase"] == "over":
            return actions
        for player in status["players"]:
            await asyncio.sleep(rng.uniform(0, pause_s))
            error, text = await call(session, "mineBlock", {"player": player, "name": "red_mushroom_block", "count": 2})
            actions += not error
            assert not error or "the run is over" in text, text
            if not error and "ended" in json.loads(text):  # in flight at the whistle: it says so
                assert json.loads(text)["ended"].startswith("the episode ended (the whistle)")
                whistles.append(status["episode"])


def records(run_dir: Path) -> list[dict]:
    return [json.loads(line) for line in (run_dir / "episodes.jsonl").read_text().splitlines()]


async def test_a_client_on_stdio_plays_three_episodes_outscores_do_nothing_and_report_reads_its_run(tmp_path):
    run_dir = tmp_path / "run"
    async with stdio_session(tmp_path, *LOCKSTEP, "episodes=3", "seed=2", f"run_dir={run_dir}") as session:
        names = [t.name for t in (await session.list_tools()).tools]
        assert {"status", "observe", "run_code", "wait", "chat", "mineBlock", "killMob"} <= set(names)
        refusals = [
            await call(session, "fly", {"player": "Ryn"}),
            await call(session, "mineBlock", {"player": "Ryn", "name": "red_mushroom_block", "count": "two"}),
            await call(session, "mineBlock", {"player": "Byte", "name": "red_mushroom_block"}),
        ]
        assert [e for e, _ in refusals] == [True, True, True]
        assert "unknown tool 'fly'" in refusals[0][1] and "mineBlock" in refusals[0][1]
        assert "count" in refusals[1][1] and "'two' is not of type 'integer'" in refusals[1][1]
        assert "'Byte' is not on the red team" in refusals[2][1]
        seen = await call(session, "observe", {"player": "Ryn"})
        assert not seen[0] and "inventory" in json.loads(seen[1])["observation"]
        whistles: list[int] = []
        assert await harvest(session, whistles=whistles) > 4
        assert whistles  # (a call that keeps a player busy to the whistle returns then, saying so)
        late = await call(session, "wait", {"player": "Ryn", "ticks": 5})
        assert late[0] and "the run is over" in late[1]
    recs = records(run_dir)
    assert [r["status"] for r in recs] == ["ok"] * 3
    assert sum(r["red_score"] for r in recs) > sum(r["blue_score"] for r in recs) == 0
    assert {r["red_entrant"]["label"] for r in recs} == {"agent:scripted/1.0"}
    calls = [json.loads(line) for line in (run_dir / "episode_000/red/tools.jsonl").read_text().splitlines()]
    assert calls[0] == {"clock": "lockstep", "window_s": 0.05}
    assert any(c.get("tool") == "mineBlock" and "tick_end" in c for c in calls[1:])
    refused = (run_dir / "episode_000/events/Ryn.jsonl").read_text()
    assert "onToolRefused" in refused and "'two' is not of type 'integer'" in refused
    report = run_cli(tmp_path, "report", str(run_dir), "--no-replays", "--out", str(tmp_path / "report"), timeout=180)
    assert report.returncode == 0, report.stderr
    assert "agent:scripted/1.0" in (tmp_path / "report" / "summary.md").read_text()
    bundle = tmp_path / "results.tar.gz"
    assert run_cli(tmp_path, "export", str(run_dir), "--out", str(bundle)).returncode == 0
    verified = run_cli(tmp_path, "verify", str(bundle))
    assert verified.returncode == 0, verified.stdout + verified.stderr


async def test_the_same_seed_plays_the_same_game_however_long_the_agent_pauses(tmp_path):
    async def play(name: str, pause_s: float) -> tuple[str, list]:
        run_dir = tmp_path / name
        async with stdio_session(tmp_path, *LOCKSTEP, "episodes=1", "seed=5", f"run_dir={run_dir}") as session:
            await harvest(session, pause_s=pause_s, seed=11)
        calls = [json.loads(line) for line in (run_dir / "episode_000/red/tools.jsonl").read_text().splitlines()]
        ticks = [(c["arguments"]["player"], c["tick_start"], c["tick_end"]) for c in calls if "tick_start" in c]
        return (run_dir / "episode_000/timeline.json").read_text(), ticks

    quick, paused = await play("quick", 0.0), await play("paused", 2.0)
    assert quick[0] == paused[0]  # the same timeline
    # every call on the same ticks (the last one's end is the whistle's, whatever it was doing)
    assert quick[1][:-1] == paused[1][:-1] and len(quick[1]) >= 3


async def test_a_client_over_http_plays_then_leaves_and_its_episode_in_play_is_finished_as_its_own(tmp_path):
    run_dir = tmp_path / "run"
    proc = subprocess.Popen(
        [*MCP, "transport=http", "port=0", *LOCKSTEP, "episodes=3", f"run_dir={run_dir}"],
        cwd=tmp_path,
        env=_env(),
        stderr=subprocess.PIPE,
        text=True,
    )
    said: list[str] = []
    try:
        reader = asyncio.create_task(asyncio.to_thread(_read, proc, said))
        while not any("serving on http" in line for line in said):
            await asyncio.sleep(0.1)
            assert proc.poll() is None, said
        url = next(line for line in said if "serving on http" in line).rsplit(" ", 1)[1].strip()
        async with streamable_http_client(url) as (read, write, *_):
            async with ClientSession(read, write, client_info=ME) as session:
                await session.initialize()
                while json.loads((await call(session, "status", {}))[1])["episode"] == 0:
                    await call(session, "mineBlock", {"player": "Ryn", "name": "red_mushroom_block", "count": 2})
                assert not (await call(session, "wait", {"player": "Ryn", "ticks": 10}))[0]  # episode 1's game
        assert await asyncio.to_thread(proc.wait, 60) == 0  # the run ended after episode 1, by itself
        await reader
    finally:
        if proc.poll() is None:
            proc.kill()
    recs = records(run_dir)
    assert [(r["episode"], r["status"]) for r in recs] == [(0, "ok"), (1, "ok")]
    assert recs[0]["red_score"] > 0 == recs[0]["blue_score"]
    assert recs[0]["red_entrant"]["label"] == "agent:scripted/1.0"
    assert any("the agent left" in p for p in recs[1]["problems"]["red"])
    assert any("2 of 3 episode(s) played" in line for line in said)


def _read(proc: subprocess.Popen, said: list[str]) -> None:
    assert proc.stderr is not None
    for line in iter(proc.stderr.readline, ""):
        said.append(line)


async def test_a_client_that_leaves_mid_series_ends_the_run_cleanly_keeping_what_it_finished(tmp_path):
    run_dir = tmp_path / "run"
    async with stdio_session(tmp_path, *LOCKSTEP, "episodes=3", f"run_dir={run_dir}") as session:
        while json.loads((await call(session, "status", {}))[1])["episode"] == 0:
            await call(session, "mineBlock", {"player": "Raze", "name": "red_mushroom_block", "count": 1})
        error, _ = await call(session, "mineBlock", {"player": "Raze", "name": "red_mushroom_block", "count": 1})
        assert not error  # in episode 1's game: the client leaves while it is played
    recs = records(run_dir)  # the command has exited within the client's grace
    assert [(r["episode"], r["status"]) for r in recs] == [(0, "ok")]
    said = (tmp_path / "mcp.stderr").read_text()
    assert "the agent left" in said and "1 of 3 episode(s) played" in said and "internal error" not in said


def test_a_bad_key_is_one_line_exit_2_and_no_run_directory(tmp_path):
    for keys, says in (
        (["side=green"], "side=green: not a side; valid: red, blue"),
        (["transport=ws"], "transport=ws: unknown; valid: stdio, http"),
        (["opponent=cott"], "unknown team 'cott'"),
        (["red=cot"], "red: not a key of `pillagerbench mcp`"),
        (["episodes=0"], "episodes"),
    ):
        done = run_cli(tmp_path, "mcp", *keys)
        assert done.returncode == 2, (keys, done.stderr)
        assert says in done.stderr and len(done.stderr.strip().splitlines()) == 1, done.stderr
        assert done.stdout == ""
    assert not (tmp_path / "runs").exists()
