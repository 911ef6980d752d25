"""`pillagerbench mcp`: a run in which the connected MCP client is a team (docs/any-agent.md).

    pillagerbench mcp                                        # stdio: red against do_nothing, Mushroom War
    pillagerbench mcp side=blue opponent=balanced episodes=3 clock=lockstep agent_model=gpt-4o
    pillagerbench mcp transport=http port=8765               # streamable HTTP on 127.0.0.1:8765/mcp

The keys of `pillagerbench run` (scenario, episodes, episode_length, clock, layout, split, seed, run_dir,
...) choose the run; this command's own: `side` (the client's, red), `opponent` (the other side's team,
do_nothing), `transport` (stdio or http), `host` and `port` (http), `agent_model` (the model behind the
client, part of its entrant). The run begins at the client's first tool call, named by the client's
declared name and version (its MCP `clientInfo`): the entrant `agent:NAME/VERSION@MODEL`. It writes the
run directory `pillagerbench run` writes (`report`, `verify`, `compare` read it). Over HTTP on a host
other than loopback every request must carry the token of `PILLAGERBENCH_MCP_TOKEN` (one is made and
shown when it is unset). Nothing of this goes to standard output, which is the MCP wire on stdio.
"""

from __future__ import annotations

import asyncio
import os
import secrets
import signal
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from pillagerbench.config.compose import ConfigError
from pillagerbench.config.schema import RunConfig
from pillagerbench.config.sides import SIDES
from pillagerbench.config.validate import load_run
from pillagerbench.experiments.plain_run import make_run_dir
from pillagerbench.experiments.series import run_series
from pillagerbench.match import preflight
from pillagerbench.match.run import scenario_from_config
from pillagerbench.mcp_front.front import LOOPBACK_HOSTS, Caller, serve
from pillagerbench.rundir import EpisodeRecord, RunDir, SeriesSpec, plain_series, progress
from pillagerbench.teams.tools import Seat, ToolResult
from pillagerbench.teams.tools.agent import open_seat, reserve_seat

TRANSPORTS = ("stdio", "http")
TOKEN_ENV = "PILLAGERBENCH_MCP_TOKEN"
LINGER_S = 3.0  # http: after the run, the server answers this long (the client reads that it is over)
NOT_HERE = ("red", "blue", "experiment", "resume", "plan")  # keys of `run` this command chooses itself


class AgentLeft(Exception):
    """The client has gone; raised once an episode is committed, so no other begins without it."""


@dataclass(frozen=True)
class McpArgs:
    side: str = "red"
    opponent: str = "do_nothing"
    transport: str = "stdio"
    host: str = "127.0.0.1"
    port: int = 0
    agent_model: str | None = None

    @property
    def other(self) -> str:
        return SIDES[1 - SIDES.index(self.side)]


def parse(argv: list[str]) -> tuple[McpArgs, list[str]]:
    """This command's own keys, and the rest (the keys of `pillagerbench run`); a bad one is a ConfigError."""
    own: dict[str, Any] = {}
    rest, problems = [], []
    for arg in argv:
        key, eq, value = arg.partition("=")
        if eq and key in McpArgs.__dataclass_fields__:
            own[key] = value
        elif eq and key.split(".")[0].lstrip("+~") in NOT_HERE:
            problems.append(f"{key}: not a key of `pillagerbench mcp` (side= and opponent= choose the teams)")
        else:
            rest.append(arg)
    if own.get("side", "red") not in SIDES:
        problems.append(f"side={own['side']}: not a side; valid: {', '.join(SIDES)}")
    if own.get("transport", "stdio") not in TRANSPORTS:
        problems.append(f"transport={own['transport']}: unknown; valid: {', '.join(TRANSPORTS)}")
    port = str(own.get("port", "0"))
    if not port.isdigit() or int(port) > 65535:
        problems.append(f"port={port}: not a port (0 to 65535; 0 = a free one)")
    if problems:
        raise ConfigError("\n".join(problems))
    own["port"] = int(port)
    return McpArgs(**own), rest


def config_of(args: McpArgs, overrides: list[str], seat_key: str) -> RunConfig:
    """The run's typed configuration, checked as `pillagerbench run` checks it."""
    chosen = [f"{args.side}=agent", f"{args.other}={args.opponent}", f"{args.side}.seat={seat_key}"]
    if args.agent_model:
        chosen.append(f"{args.side}.agent_model={args.agent_model}")
    return load_run([*overrides, *chosen])


def say(line: str) -> None:
    print(f"pillagerbench mcp: {line}", file=sys.stderr, flush=True)


class McpRun:
    """The run behind the server: begun by the client's first call, as the entrant the client declares."""

    def __init__(self, args: McpArgs, cfg: RunConfig, seat: Seat):
        self.args, self.cfg, self.seat = args, cfg, seat
        self.task: asyncio.Task | None = None
        self.run_dir: Path | None = None

    async def call(self, caller: Caller, name: str, arguments: dict[str, Any]) -> ToolResult:
        if self.task is None:
            self.begin(caller)
        return await self.seat.call(name, arguments)

    def begin(self, caller: Caller) -> None:
        cfg = self.cfg.updated({self.args.side: {"agent": caller.name, "agent_version": caller.version}})
        self.run_dir = run_dir = make_run_dir(cfg)
        run_dir.mkdir(parents=True, exist_ok=True)
        say(f"{caller.name} {caller.version} plays {self.args.side}; run directory: {run_dir}")
        spec = plain_series(cfg.for_series(), run_dir.name)
        self.task = asyncio.create_task(self._play(spec, run_dir))

    async def _play(self, spec: SeriesSpec, run_dir: Path) -> None:
        try:
            await run_series(spec, run_dir, say=say, on_episode=self._done)
        except AgentLeft:
            say("the agent left: the run ended after its episode")
        except asyncio.CancelledError:
            say("the agent left: the run ends; its episode in play is not finished (not recorded), the rest is kept")
        finally:
            self.seat.finish()
            self.summary()

    def _done(self, rec: EpisodeRecord) -> None:
        say(f"episode {rec.episode}: {rec.status}, red {rec.red_score} - blue {rec.blue_score}")
        if self.seat.left:  # (called once the episode is committed: the run ends here, beginning no other)
            raise AgentLeft()

    def left(self) -> None:
        """The client's HTTP session has ended: its players idle to the end of the episode in play, which is
        recorded as the team's, and the run ends."""
        if self.task is not None and not self.task.done():
            say("the agent's session ended: its players idle to the end of this episode, then the run ends")
            self.seat.leave()

    async def end(self) -> None:
        """The client has gone (on stdio it closed our input, and kills our process group 2 s later, as MCP's
        stdio transport has it): the run ends now. Its episode in play is not finished and not recorded, as a
        killed run's; every finished one is kept."""
        if self.task is None:
            return
        self.seat.leave()
        while not self.task.done():  # (a cancel that lands with a reply can be swallowed: CPython gh-86296)
            self.task.cancel()
            await asyncio.wait([self.task], timeout=0.5)

    def summary(self) -> None:
        if self.run_dir is None:
            return
        finished = RunDir(self.run_dir).finished()
        done = progress(finished, self.cfg.episodes, self.cfg.retries)
        say(f"{done.used} of {self.cfg.episodes} episode(s) played; run directory: {self.run_dir}")


async def _serve(args: McpArgs, run: McpRun, token: str | None) -> None:
    stop = asyncio.Event()
    server = asyncio.create_task(
        serve(
            run.seat.tools,
            run.call,
            transport=args.transport,
            host=args.host,
            port=args.port,
            token=token,
            on_ready=lambda where: say(f"serving on {where}"),
            stop=stop,
            on_session_end=run.left,
        )
    )
    asyncio.get_running_loop().add_signal_handler(signal.SIGTERM, server.cancel)  # as a client that left
    while not server.done():
        await asyncio.wait([server], timeout=0.5)
        if args.transport == "http" and run.task is not None and run.task.done():
            await asyncio.sleep(LINGER_S)  # the client reads that the run is over
            stop.set()
            await server
    await run.end()  # stdio: the client has gone


def token_of(args: McpArgs) -> str | None:
    if args.transport != "http" or args.host in LOOPBACK_HOSTS and not os.environ.get(TOKEN_ENV):
        return None
    token = os.environ.get(TOKEN_ENV) or secrets.token_urlsafe(24)
    if not os.environ.get(TOKEN_ENV):
        say(f"requests must carry 'Authorization: Bearer {token}' (set {TOKEN_ENV} to choose it)")
    return token


def main(argv: list[str]) -> int:
    args, overrides = parse(argv)
    key = reserve_seat()  # the config names the seat; the seat needs the config's scenario
    cfg = config_of(args, overrides, key)
    seat = Seat(scenario_from_config(cfg), args.side)
    open_seat(seat, key)
    preflight.check([s for s in preflight.sides_of(cfg) if s[0] != "agent"])  # the opponent can play
    asyncio.run(_serve(args, McpRun(args, cfg, seat), token_of(args)))
    return 0
