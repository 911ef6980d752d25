"""`remote`: a team that lives outside the benchmark, in any language, reached over HTTP with the
protocol of `protocol.py` (docs/remote-teams.md).

Pre-game: the team gets the scenario, the primitives' docs, each player's observation and the last
episode, and answers one program per player. The game: every player runs its program (started
again when it ends, after `restart_pause_s`); every `events_every_s` the players' new events go to
the team, which may answer new programs (a player's running program is then stopped and the new one
started). Post-game: the episode record. The team's time counts like an LLM's: pre-game is timed,
in-game answers arrive while the clock runs.

A refused connection, a time-out, a broken (cut), malformed or oversized answer, a wrong player
name: recorded in `problems` (so in episodes.jsonl) and the team plays on; a player without a program idles.
"""

from __future__ import annotations

import asyncio
import http.client
import json
import time
import urllib.error
import urllib.request
from typing import Any, TypeVar
from urllib.parse import urlparse

from pydantic import BaseModel, Field, ValidationError

from pillagerbench.players import primitives as prim
from pillagerbench.rundir import last_seen_json
from pillagerbench.teams.base import Team, TeamContext
from pillagerbench.teams.options import TeamOptions, defaults
from pillagerbench.teams.remote import wire as P


class RemoteOptions(TeamOptions):
    """remote's options (`red.KEY=VALUE`; docs/remote-teams.md lists them)."""

    url: str | None = Field(default=None, description="http(s)://HOST:PORT of the team server (required)")
    pregame_timeout_s: float = Field(
        default=60.0, gt=0, description="the pre-game answer (like an LLM's planning call)"
    )
    call_timeout_s: float = Field(default=5.0, gt=0, description="each in-game and post-game call")
    events_every_s: float = Field(default=1.0, gt=0, description="how often the players' events are sent")
    max_answer_bytes: int = Field(default=1_000_000, ge=1, description="a larger answer is refused")
    restart_pause_s: float = Field(
        default=1.0, ge=0, description="wait before starting again a program that ended within this time"
    )


DEFAULTS: dict[str, Any] = defaults(RemoteOptions)


Reply = TypeVar("Reply", bound=BaseModel)
# the episode's last call (its post-game) recorded as a problem holding one of these: the team server did not
# answer at all at the episode's end (refused, name not resolved, cut, a 5xx); a series then waits for it
# before its next episode (experiments/outage.py). A time-out is not one: a slow team's answers are its own.
UNREACHABLE = ("cannot reach ", "broken answer from ", "HTTP 5")


class RemoteError(Exception):
    """A call to the team server failed; the message says how."""


def _http(method: str, url: str, body: bytes | None, timeout: float, limit: int) -> bytes:
    request = urllib.request.Request(
        url, data=body, method=method, headers={"Content-Type": "application/json"} if body else {}
    )
    try:
        with urllib.request.urlopen(request, timeout=timeout) as response:
            data = response.read(limit + 1)
    except urllib.error.HTTPError as exc:
        raise RemoteError(f"HTTP {exc.code} from {url}") from None
    except (urllib.error.URLError, OSError) as exc:
        reason = getattr(exc, "reason", exc)
        if isinstance(reason, TimeoutError):
            raise RemoteError(f"no answer from {url} within {timeout:g} s") from None
        raise RemoteError(f"cannot reach {url}: {reason}") from None
    except http.client.HTTPException as exc:  # e.g. the server died mid-answer (IncompleteRead)
        raise RemoteError(f"broken answer from {url}: {exc!r}") from None
    if len(data) > limit:
        raise RemoteError(f"answer from {url} is larger than max_answer_bytes={limit}")
    return data


async def call(
    url: str,
    path: str,
    message: BaseModel | None,
    reply: type[Reply],
    *,
    timeout: float,
    limit: int = DEFAULTS["max_answer_bytes"],
) -> Reply:
    """One protocol call; raises RemoteError naming what went wrong."""
    target = url.rstrip("/") + path
    body = message.model_dump_json().encode() if message is not None else None
    try:
        raw = await asyncio.wait_for(
            asyncio.to_thread(_http, "POST" if body else "GET", target, body, timeout, limit), timeout + 1.0
        )
    except asyncio.TimeoutError:
        raise RemoteError(f"no answer from {target} within {timeout:g} s") from None
    try:
        return reply.model_validate_json(raw)
    except ValidationError as exc:
        first = exc.errors(include_url=False)[0]
        where = ".".join(map(str, first["loc"])) or "the answer"
        raise RemoteError(f"malformed answer from {target}: {where}: {first['msg']}") from None


class RemoteTeam(Team):
    name = "remote"
    Options = RemoteOptions

    def __init__(self, **options: object):
        super().__init__(**options)
        o = RemoteOptions.model_validate(options)
        self.url = o.url or ""
        self.pregame_timeout_s, self.call_timeout_s = o.pregame_timeout_s, o.call_timeout_s
        self.events_every_s, self.max_answer_bytes = o.events_every_s, o.max_answer_bytes
        self.restart_pause_s = o.restart_pause_s
        self.programs: dict[str, str] = {}
        self.versions: dict[str, int] = {}
        self.record: dict[str, Any] = {}
        self._t0 = time.monotonic()

    # --- checks before the run ----------------------------------------------------------------
    @classmethod
    def check_options(cls, options: dict[str, Any]) -> list[str]:
        url = options.get("url")
        if not url:
            return ["url: the remote team needs the address of its server, e.g. red.url=http://127.0.0.1:8800"]
        parsed = urlparse(str(url))
        if parsed.scheme not in ("http", "https") or not parsed.netloc:
            return [f"url={url!r}: not an http(s) address; give e.g. http://127.0.0.1:8800"]
        return []

    @classmethod
    async def preflight(cls, options: dict[str, Any]) -> str | None:
        url = str(options.get("url"))
        try:
            hello = await call(url, "/", None, P.Hello, timeout=5.0)
        except RemoteError as exc:
            return f"remote team at {url} does not answer: {exc} (start the team server first, or fix url=)"
        if getattr(hello, "protocol", None) != P.PROTOCOL:
            return (
                f"remote team at {url} speaks protocol {hello.protocol}, the benchmark speaks {P.PROTOCOL} "
                "(docs/remote-teams.md)"
            )
        return None

    @classmethod
    def unreachable(cls, problems: list[str]) -> bool:
        """Whether a side's recorded problems say its team server could not be reached at the episode's end
        (its post-game call, `UNREACHABLE`): a series probes it (`preflight`) and waits for it before its next
        episode (docs/experiments.md). A call that failed mid-game, the server answering again, is not."""
        return any(p.startswith("remote /postgame: ") and any(u in p for u in UNREACHABLE) for p in problems)

    # --- calls ---------------------------------------------------------------------------------
    async def _call(self, path: str, message: BaseModel, reply: type[BaseModel], timeout: float) -> Any:
        t0 = time.monotonic()
        entry: dict[str, Any] = {"path": path, "at_s": round(t0 - self._t0, 3)}
        self.record.setdefault("calls", []).append(entry)
        try:
            answer = await call(self.url, path, message, reply, timeout=timeout, limit=self.max_answer_bytes)
        except RemoteError as exc:
            entry["error"] = str(exc)
            self.problems.append(f"remote {path}: {exc}")
            return None
        finally:
            entry["latency_s"] = round(time.monotonic() - t0, 4)
        return answer

    def _take(self, ctx: TeamContext, answer: Any) -> list[str]:
        """Accept the programs of an answer for this side's players; returns who got a new one."""
        if answer is None:
            return []
        changed = []
        for name, code in answer.programs.items():
            if name not in ctx.side.player_names:
                self.problems.append(
                    f"remote answer names {name!r}, not a player of this team "
                    f"({', '.join(ctx.side.player_names)}); ignored"
                )
                continue
            self.programs[name] = code
            self.versions[name] = self.versions.get(name, 0) + 1
            changed.append(name)
        return changed

    # --- phases --------------------------------------------------------------------------------
    async def pre_game(self, ctx: TeamContext) -> None:
        self.record = {"episode": ctx.episode, "url": self.url}
        self._t0 = time.monotonic()
        self.programs, self.versions = {}, {}
        sc, side = ctx.scenario, ctx.side
        modules = list(sc.primitives)
        message = P.PregameRequest(
            episode=ctx.episode,
            episode_length_s=ctx.episode_length,
            scenario=P.ScenarioInfo(key=sc.key, title=sc.title, description=sc.description()),
            side=P.SideInfo(
                key=side.key,
                team_name=side.team_name,
                players=[P.PlayerInfo(name=p.name, spawn=list(p.spawn)) for p in side.players],
                opponent_team_name=ctx.opponent.team_name,
                opponent_players=ctx.opponent.player_names,
            ),
            primitives=prim.functions(modules),
            primitives_docs=prim.docs([*modules, "mineflayer"]),
            observations={
                n: (obs[-1][1] if obs and obs[-1][0] == "observe" else {}) for n, obs in ctx.observations.items()
            },
            last_episode=_jsonable(last_seen_json(ctx.last_episode)) if ctx.last_episode else None,
        )
        self._take(ctx, await self._call("/pregame", message, P.Programs, self.pregame_timeout_s))

    async def play(self, ctx: TeamContext) -> None:
        names = ctx.side.player_names
        self.iterations = [0] * len(names)
        outbox: dict[str, list] = {n: [] for n in names}
        start = ctx.clock.now()
        runners = [asyncio.create_task(self._keep_running(ctx, k, n, outbox)) for k, n in enumerate(names)]
        try:
            while ctx.time_left() > 0:
                await ctx.sleep(self.events_every_s)
                batch = {n: evs for n, evs in outbox.items() if evs}
                if not batch:
                    continue
                for n in batch:
                    outbox[n] = []
                message = P.EventsRequest(
                    episode=ctx.episode,
                    t=round(ctx.clock.now() - start, 3),
                    time_left_s=round(ctx.time_left(), 3),
                    events=_jsonable(batch),
                )
                async with ctx.clock.thinking(ctx.side.key):  # lockstep: the world waits for the answer
                    answer = await self._call("/events", message, P.Programs, self.call_timeout_s)
                for name in self._take(ctx, answer):
                    await ctx.players[name].stop()  # its runner starts the new program
        finally:
            for task in runners:
                task.cancel()
            await asyncio.gather(*runners, return_exceptions=True)

    async def _keep_running(self, ctx: TeamContext, k: int, name: str, outbox: dict[str, list]) -> None:
        player = ctx.players[name]
        while ctx.time_left() > 0:
            code = self.programs.get(name)
            if not code:  # no program (yet): idle until one arrives
                await ctx.sleep(0.2, name)
                continue
            version = self.versions.get(name)
            self.iterations[k] += 1
            started, failed = ctx.clock.now(), False
            try:
                await player.run(code, on_event=lambda event: outbox[name].append(event))
            except Exception as exc:  # noqa: BLE001 - the bot cannot run code right now: note it and go on
                failed = True
                self.problems.append(f"{name}: {type(exc).__name__}: {exc}")
            # a new program starts at once; the same one after the pause (a failed start: a tick at least)
            await ctx.pause_before_rerun(
                name, 0.0 if self.versions.get(name) != version else self.restart_pause_s, started, failed
            )

    async def post_game(self, ctx: TeamContext) -> None:
        last = last_seen_json(ctx.last_episode) if ctx.last_episode else {}
        message = P.PostgameRequest(
            episode=ctx.episode, record=_jsonable(last.get("record") or {}), chat=list(last.get("chat") or [])
        )
        await self._call("/postgame", message, P.Ack, self.call_timeout_s)
        self.record["programs"] = dict(self.programs)
        self.record["problems"] = list(self.problems)
        ctx.out_dir.mkdir(parents=True, exist_ok=True)
        (ctx.out_dir / "remote.json").write_text(json.dumps(self.record, indent=1, default=str))


def _jsonable(value: Any) -> Any:
    return json.loads(json.dumps(value, default=str))
