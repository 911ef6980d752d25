"""The game as tools (issue "Any agent plays"): what a tool call costs, and what an agent's episode costs.

    python benchmarks/tool_calls.py [--calls 40] [--episode-length 30]

1. One call's wall time, the median of --calls, on the real clock (no window: the world runs on), each
   an empty program on a player's bot (`run_code` with code ""), and `status` (no game action):
   - `code`: the same empty program run through the player's handle, as a built-in team runs code;
   - `seat`: through the seat in process (our `tools` team calls it so);
   - `inspect`: one model turn's call run by Inspect's `execute_tools` (as `react()` runs it) on the seat's
     Inspect tools;
   - `mcp_stdio`, `mcp_http`: from the official SDK's client to `pillagerbench mcp`.
2. A lockstep episode's wall time (the game only: the record's duration less its reset and pre-game):
   a Python team (both players harvest, each in a loop of one `mineBlock` program and a 1 s wait) and the
   same actions by an MCP client on stdio (`mineBlock`, `wait`; two calls in flight, one per player), on
   the same seed.

Prints JSON.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))
sys.path.insert(0, str(ROOT))

from inspect_ai.model import ChatMessageAssistant, execute_tools  # noqa: E402
from inspect_ai.tool import ToolCall  # noqa: E402
from mcp import ClientSession, StdioServerParameters  # noqa: E402
from mcp.client.stdio import stdio_client  # noqa: E402
from mcp.client.streamable_http import streamable_http_client  # noqa: E402
from mcp.types import Implementation  # noqa: E402

from pillagerbench.inspect_tasks.tools import seat_tools  # noqa: E402
from pillagerbench.scenarios import make_scenario  # noqa: E402
from pillagerbench.teams import Team, TeamContext  # noqa: E402
from pillagerbench.teams.tools import AgentTeam, Seat  # noqa: E402
from pillagerbench.teams.tools.agent import open_seat  # noqa: E402
from pillagerbench.teams.tools.surface import call_code, primitives_of  # noqa: E402
from tests.teams.conftest import play_series  # noqa: E402

MCP = [sys.executable, "-m", "pillagerbench.cli", "mcp"]
ME = Implementation(name="bench", version="1")
_RED = make_scenario("mushroom_war").placeholders("red")
HARVEST = {  # what examples/scripted_team.py harvests: red's mushrooms, 4 a trip, within its area
    "name": _RED["team_block"],
    "count": 4,
    "point": [int(v) for v in _RED["team_center"].split(",")],
    "maxDistance": _RED["area_radius"],
}


def _median_ms(times: list[float]) -> float:
    return round(statistics.median(times) * 1000, 2)


async def _timed(n: int, call) -> list[float]:
    out = []
    for _ in range(n):
        t0 = time.perf_counter()
        await call()
        out.append(time.perf_counter() - t0)
    return out


async def in_process(n: int) -> dict[str, float]:
    """`code` and `seat`: one real-clock episode, an in-process agent timing both."""
    seat = Seat(make_scenario("mushroom_war"), "red")
    team = AgentTeam(seat=open_seat(seat), pregame_timeout_s=30)
    found: dict[str, float] = {}

    async def agent() -> None:
        await seat.call("status")
        await seat.call("wait", {"player": "Ryn", "ticks": 1})  # the game is on
        handle = seat.ctx.players["Ryn"] if seat.ctx else None
        assert handle is not None
        tools = seat_tools(seat)
        turn = ChatMessageAssistant(
            content="", tool_calls=[ToolCall(id="1", function="run_code", arguments={"player": "Ryn", "code": ""})]
        )
        code, seated, inspect = [], [], []
        for _ in range(n):  # interleaved: none has the warm-up to itself
            code += await _timed(1, lambda: handle.run(""))
            seated += await _timed(1, lambda: seat.call("run_code", {"player": "Ryn", "code": ""}))
            inspect += await _timed(1, lambda: execute_tools([turn], tools))  # as react() runs a turn's calls
        found["code"], found["seat"], found["inspect"] = _median_ms(code), _median_ms(seated), _median_ms(inspect)
        found["seat_status"] = _median_ms(await _timed(n, lambda: seat.call("status")))

    task = asyncio.create_task(agent())
    length = 20 + n * 0.2
    await play_series("mushroom_war", team, "do_nothing", Path(tempfile.mkdtemp(prefix="pb-tools-")), length=length)
    seat.finish()
    await task
    return found


async def _mcp_calls(session: ClientSession, n: int) -> dict[str, float]:
    await session.call_tool("wait", {"player": "Ryn", "ticks": 1})  # begins the run, waits for its game
    run = await _timed(n, lambda: session.call_tool("run_code", {"player": "Ryn", "code": ""}))
    status = await _timed(n, lambda: session.call_tool("status", {}))
    return {"run_code": _median_ms(run), "status": _median_ms(status)}


async def mcp_stdio(n: int) -> dict[str, float]:
    keys = ["clock=real", f"episode_length={20 + n * 0.2}", f"run_dir={tempfile.mkdtemp(prefix='pb-tools-')}"]
    params = StdioServerParameters(command=MCP[0], args=[*MCP[1:], *keys])
    async with stdio_client(params, errlog=subprocess.DEVNULL) as (read, write):  # type: ignore[arg-type]
        async with ClientSession(read, write, client_info=ME) as session:
            await session.initialize()
            return await _mcp_calls(session, n)


async def mcp_http(n: int) -> dict[str, float]:
    keys = ["transport=http", "clock=real", f"episode_length={20 + n * 0.2}"]
    proc = subprocess.Popen(
        [*MCP, *keys, f"run_dir={tempfile.mkdtemp(prefix='pb-tools-')}"], stderr=subprocess.PIPE, text=True
    )
    try:
        assert proc.stderr is not None
        url = next(line.rsplit(" ", 1)[1].strip() for line in proc.stderr if "serving on http" in line)
        async with streamable_http_client(url) as (read, write, *_):
            async with ClientSession(read, write, client_info=ME) as session:
                await session.initialize()
                return await _mcp_calls(session, n)
    finally:
        proc.terminate()
        proc.wait()


def _game_wall(rec: dict[str, Any]) -> dict[str, Any]:
    game = rec["duration_s"] - rec["reset_s"] - max(rec["pre_game_s"].values())
    return {"game_wall_s": round(game, 2), "red_score": rec["red_score"]}


class SameActions(Team):
    """The MCP agent's actions as a Python team: each player, in a loop, the `mineBlock` line its tool call
    stands for, then a wait of 20 ticks."""

    name = "same_actions"

    async def play(self, ctx: TeamContext) -> None:
        mine = next(p for p in primitives_of(["mineBlock"]) if p.name == "mineBlock")
        code = call_code(mine, HARVEST)

        async def keep_harvesting(name: str) -> None:
            while ctx.time_left() > 0:
                await ctx.players[name].run(code)
                await ctx.sleep(1.0, player=name)

        await asyncio.gather(*(keep_harvesting(n) for n in ctx.side.player_names))


async def scripted_episode(length: float) -> dict[str, Any]:
    run_dir = Path(tempfile.mkdtemp(prefix="pb-tools-"))
    recs = await play_series(
        "mushroom_war", SameActions(), "do_nothing", run_dir, length=length, clock="lockstep", seed=4
    )
    return _game_wall(recs[0].to_dict())


async def mcp_episode(length: float) -> dict[str, Any]:
    run_dir = Path(tempfile.mkdtemp(prefix="pb-tools-"))
    keys = ["clock=lockstep", f"episode_length={length}", "seed=4", f"run_dir={run_dir}"]
    params = StdioServerParameters(command=MCP[0], args=[*MCP[1:], *keys])
    async with stdio_client(params, errlog=subprocess.DEVNULL) as (read, write):  # type: ignore[arg-type]
        async with ClientSession(read, write, client_info=ME) as session:
            await session.initialize()

            async def keep_harvesting(player: str) -> None:
                while True:
                    done = await session.call_tool("mineBlock", {"player": player, **HARVEST})
                    if done.is_error:
                        return
                    await session.call_tool("wait", {"player": player, "ticks": 20})

            await asyncio.gather(*(keep_harvesting(p) for p in ("Ryn", "Raze")))
    return _game_wall(json.loads((run_dir / "episodes.jsonl").read_text().splitlines()[0]))


async def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=40)
    parser.add_argument("--episode-length", type=float, default=30.0)
    args = parser.parse_args()
    out: dict[str, Any] = {"calls": args.calls}
    out["lockstep_episode"] = {
        "episode_length_s": args.episode_length,
        "python_team": await scripted_episode(args.episode_length),
        "mcp_stdio_agent": await mcp_episode(args.episode_length),
    }
    out["per_call_ms"] = {
        "in_process": await in_process(args.calls),
        "mcp_stdio": await mcp_stdio(args.calls),
        "mcp_http": await mcp_http(args.calls),
    }
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    asyncio.run(main())
