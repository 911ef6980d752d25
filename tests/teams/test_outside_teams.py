"""Teams from outside the package: import paths, entry points, bad input in one line, and a remote
team server that misbehaves in every way the protocol allows (the match plays on)."""

from __future__ import annotations

import json
import sys
import threading
import time
from contextlib import contextmanager
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path

import pytest

from pillagerbench.config.compose import ConfigError
from pillagerbench.teams import find_team
from pillagerbench.teams.remote import RemoteTeam
from pillagerbench.teams.remote.wire import schemas
from tests.support.cli import refused_in_process, run_cli
from tests.teams.conftest import play_series

ROOT = Path(__file__).resolve().parents[2]

TEAM_MODULE = """
from pillagerbench.teams import Team

class Idle(Team):
    name = "idle"
    options_declared = {"patience": 3}

NOT_A_TEAM = 42
"""


@pytest.fixture
def outside(tmp_path):
    """A folder on PYTHONPATH with a team module and two installed distributions with entry points."""
    (tmp_path / "my_teams.py").write_text(TEAM_MODULE)
    (tmp_path / "broken_team.py").write_text("raise RuntimeError('this package is broken')\n")
    for dist, entries in (
        ("good_dist", "idle_ep = my_teams:Idle\ndup = my_teams:Idle\nbad = broken_team:X\n"),
        ("other_dist", "dup = my_teams:Idle\n"),
    ):
        info = tmp_path / f"{dist}-1.0.dist-info"
        info.mkdir()
        (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {dist}\nVersion: 1.0\n")
        (info / "entry_points.txt").write_text(f"[pillagerbench.teams]\n{entries}")
    return tmp_path


def pb(cwd, path, *args):
    return run_cli(cwd, *args, env={"PYTHONPATH": str(path)})


def test_teams_lists_entry_points_with_options(outside, tmp_path):
    proc = pb(tmp_path, outside, "teams")
    assert proc.returncode == 0, proc.stderr
    idle = next(line for line in proc.stdout.splitlines() if line.startswith("idle_ep"))
    assert "entry point my_teams:Idle" in idle and "patience=3" in idle
    assert any(line.startswith("remote ") and "url=null" in line for line in proc.stdout.splitlines())
    assert any(line.startswith("dup") and "broken: two teams" in line for line in proc.stdout.splitlines())


@pytest.mark.parametrize(
    "args, expected",
    [
        (["red=my_teams:Nope"], "red=my_teams:Nope: team 'my_teams:Nope': module my_teams has no Nope"),
        (["red=my_teams:NOT_A_TEAM"], "team 'my_teams:NOT_A_TEAM' is 42, not a team: it must be a subclass"),
        (["red=no_such_pkg.mod:X"], "cannot import no_such_pkg.mod: ModuleNotFoundError"),
        (
            ["red=bad"],
            "team 'bad': its entry point broken_team:X failed to import: RuntimeError: this package is broken",
        ),
        (["red=dup"], "two teams are registered under the name 'dup'"),
        (["red=my_teams:Idle", "red.patiense=2"], "red.patiense: unknown key (options of my_teams:Idle: patience)"),
        (["red=idle_ep", "red.patience=soon"], "red.patience='soon': input should be a valid integer"),
        (["red=remote", "red.url=ftp://x"], "red.url='ftp://x': not an http(s) address"),
        (["red=remote"], "red.url: the remote team needs the address of its server"),
        (["red=remote", "red.url=http://127.0.0.1:9"], "remote team at http://127.0.0.1:9 does not answer"),
    ],
)
def test_bad_outside_teams_are_one_line_before_anything_starts(outside, monkeypatch, capsys, args, expected):
    # in-process (cli.main), the folder on sys.path as PYTHONPATH puts it on the command's: a subprocess per
    # case paid seconds of imports; `teams` above and the command's refusal end to end
    # (tests/test_cli_errors.py) still go through the real command
    monkeypatch.syspath_prepend(str(outside))
    try:
        refused(monkeypatch, capsys, expected, outside, "run", *args)
    finally:
        sys.modules.pop("my_teams", None)  # each test's folder imports its own


def refused(monkeypatch, capsys, expected: str, cwd: Path, *argv: str) -> None:
    """The command refuses in-process in `cwd` (tests/support/cli.py) in one line saying `expected`."""
    (line,) = refused_in_process(monkeypatch, capsys, cwd, *argv)
    assert expected in line, line


def test_an_import_path_and_an_entry_point_reach_the_same_class(outside, monkeypatch):
    monkeypatch.syspath_prepend(str(outside))
    import importlib

    importlib.invalidate_caches()
    assert find_team("my_teams:Idle") is find_team("idle_ep")
    with pytest.raises(ConfigError, match="known: .*remote.*or an import path"):
        find_team("nobody")


def test_the_documented_schemas_are_the_protocol_models():
    doc = (ROOT / "docs" / "remote-teams.md").read_text()
    for name, schema in schemas().items():
        assert f"### `{name}`\n\n```json\n{json.dumps(schema, indent=1)}\n```" in doc, name


class TeamServer(BaseHTTPRequestHandler):
    """A remote team server for tests: answers `reply(path, body)`; GET / says protocol 1."""

    protocol = 1
    calls: list[str]

    def answer(self, raw: bytes, status: int = 200) -> None:
        self.send_response(status)
        self.send_header("Content-Length", str(len(raw)))
        self.end_headers()
        self.wfile.write(raw)

    def do_GET(self):
        self.answer(json.dumps({"protocol": self.protocol}).encode())

    def do_POST(self):
        body = json.loads(self.rfile.read(int(self.headers["Content-Length"])))
        self.calls.append(self.path)
        if self.path == "/pregame":
            me = body["side"]["players"][0]["name"]
            return self.answer(
                json.dumps({"programs": {"Stranger": "bot.chat('x')", me: program("first program")}}).encode()
            )
        if self.path == "/postgame":
            return self.answer(b"{}")
        self.on_events(self.calls.count("/events"), body)

    def on_events(self, n: int, body: dict) -> None:
        self.answer(b"{}")

    def log_message(self, *args):
        pass


def program(label: str) -> str:
    """Chat `label`, then chat forever (so the player always has new events to send)."""
    return f"bot.chat('{label}'); while (true) {{ await bot.waitForTicks(10); bot.chat('tick') }}"


def programs_for_the_player(body: dict, label: str) -> bytes:
    return json.dumps({"programs": {name: program(label) for name in body["events"]}}).encode()


@contextmanager
def team_server(handler: type[TeamServer]):
    """Serve `handler` on a free loopback port; yields its url."""
    handler.calls = []
    server = ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        server.server_close()


class Misbehaving(TeamServer):
    """Pre-game: a program for a stranger and one for a real player; then, in turn, a malformed
    answer, a new program, an oversized answer, a late one, an HTTP 500, and another new program."""

    def on_events(self, n: int, body: dict) -> None:
        if n == 1:
            return self.answer(b"this is not json")
        if n == 2:
            return self.answer(programs_for_the_player(body, "after the malformed answer"))
        if n == 3:
            return self.answer(b'{"programs": {"x": "' + b"a" * 3000 + b'"}}')
        if n == 4:
            time.sleep(1.5)
            return self.answer(b"{}")
        if n == 5:
            return self.answer(b"{}", status=500)
        if n == 6:
            return self.answer(programs_for_the_player(body, "after the HTTP 500"))
        return self.answer(b"{}")


def test_a_misbehaving_team_server_is_recorded_and_the_match_plays_on(tmp_path):
    with team_server(Misbehaving) as url:
        proc = run_cli(
            tmp_path,
            "run",
            "red=remote",
            f"red.url={url}",
            "red.call_timeout_s=0.5",
            "red.max_answer_bytes=2000",
            "red.events_every_s=0.5",
            "blue=do_nothing",
            "episode_length=12",
            "display=plain",
            "run_dir=out",
            timeout=240,
        )
    assert proc.returncode in (0, 1), proc.stdout + proc.stderr
    rec = json.loads((tmp_path / "out" / "episodes.jsonl").read_text())
    assert rec["status"] == "ok"
    problems = "\n".join(rec["problems"]["red"])
    assert "remote answer names 'Stranger', not a player of this team" in problems
    assert "malformed answer" in problems
    assert "larger than max_answer_bytes=2000" in problems
    assert "no answer from" in problems and "within 0.5 s" in problems
    assert "HTTP 500" in problems
    chat = (tmp_path / "out" / "episode_000" / "chat.txt").read_text()
    assert "first program" in chat  # the good program of the pre-game ran
    # it plays on: the team kept calling after each failure, and the programs it answered later ran
    assert "after the malformed answer" in chat and "after the HTTP 500" in chat
    assert Misbehaving.calls[0] == "/pregame" and Misbehaving.calls[-1] == "/postgame"


class FromTheFuture(TeamServer):
    protocol = 2


def test_a_team_server_speaking_another_protocol_is_refused_in_one_line(tmp_path, monkeypatch, capsys):
    with team_server(FromTheFuture) as url:
        expected = f"remote team at {url} speaks protocol 2, the benchmark speaks 1"
        argv = ("run", "red=remote", f"red.url={url}", "blue=do_nothing", "episode_length=10")
        refused(monkeypatch, capsys, expected, tmp_path, *argv)
    assert FromTheFuture.calls == []  # asked GET / only: no episode began


class DiesMidGame(TeamServer):
    """Answers the first events; killed while answering the second: the answer is cut short and
    every later call is refused."""

    def on_events(self, n: int, body: dict) -> None:
        if n == 1:
            return self.answer(b"{}")
        self.wfile.write(b'HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\n40\r\n{"programs"')
        self.close_connection = True
        server = self.server
        threading.Thread(target=lambda: (server.shutdown(), server.server_close())).start()


async def test_a_team_server_that_dies_mid_game_is_a_problem_and_the_episode_finishes(tmp_path):
    with team_server(DiesMidGame) as url:
        team = RemoteTeam(url=url, call_timeout_s=0.5, events_every_s=0.5)
        (rec,) = await play_series("mushroom_war", team, "do_nothing", tmp_path, length=12)
    assert rec.status == "ok", rec.error
    assert json.loads((tmp_path / "episode_000" / "timeline.json").read_text())[-1]["t"] == 12
    problems = rec.problems["red"]
    assert any(p.startswith(f"remote /events: broken answer from {url}/events") for p in problems), problems
    # the team played on: it called again (refused now) until the whistle, then the post-game
    assert any(p.startswith(f"remote /events: cannot reach {url}/events") for p in problems), problems
    assert problems[-1].startswith(f"remote /postgame: cannot reach {url}/postgame"), problems
    assert DiesMidGame.calls == ["/pregame", "/events", "/events"]


class Throws(TeamServer):
    """Pre-game: both players get a program that throws, one at once, one after a wait; the team
    answers every /events with nothing new, and keeps what it was sent."""

    PROGRAMS = (
        "bot.chat('attempt at once'); throw new Error('thrown at once')",
        "await bot.waitForTicks(5); bot.chat('attempt after a wait'); throw new Error('thrown after a wait')",
    )
    received: list[dict]

    def do_POST(self):
        if self.path != "/pregame":
            return super().do_POST()
        body = json.loads(self.rfile.read(int(self.headers["Content-Length"])))
        self.calls.append(self.path)
        names = [p["name"] for p in body["side"]["players"]]
        self.answer(json.dumps({"programs": dict(zip(names, self.PROGRAMS, strict=True))}).encode())

    def on_events(self, n: int, body: dict) -> None:
        self.received.append(body["events"])
        self.answer(b"{}")


async def test_a_remote_players_program_that_throws_is_started_again_within_the_episode(tmp_path):
    Throws.received = []
    with team_server(Throws) as url:
        team = RemoteTeam(url=url, events_every_s=0.5, restart_pause_s=0.5)
        (rec,) = await play_series("mushroom_war", team, "do_nothing", tmp_path, length=10)
    assert rec.status == "ok", rec.error
    at_once, after_a_wait = rec.runs  # both players of red, in the scenario's order
    chat = (tmp_path / "episode_000" / "chat.txt").read_text()
    for name, said, thrown in (
        (at_once, "attempt at once", "Error: thrown at once"),
        (after_a_wait, "attempt after a wait", "Error: thrown after a wait"),
    ):
        assert rec.runs[name] >= 3, rec.runs  # run again after each throw, within the 10 s
        assert chat.count(said) >= 3, chat
        sent = [e for batch in Throws.received for e in batch.get(name, [])]
        errors_sent = [e[1]["onError"] for e in sent if e[0] == "onError"]
        assert len(errors_sent) >= 3 and all(err.startswith(thrown) for err in errors_sent), errors_sent
    assert rec.problems.get("red", []) == []  # a throw is the program's, not a failure of the protocol


class Slow(TeamServer):
    """Answers every /events call after 0.4 s of wall time."""

    def on_events(self, n: int, body: dict) -> None:
        time.sleep(0.4)
        self.answer(b"{}")


def test_on_the_lockstep_clock_a_slow_team_server_costs_no_game_time(tmp_path):
    """Issue 38: a remote team's call holds the world, so a team server 0.4 s slow still gets its
    events every 0.5 s of game (about 16 calls in 8 s of game; on the real clock, about 9)."""
    with team_server(Slow) as url:
        proc = run_cli(
            tmp_path, "run", "red=remote", f"red.url={url}", "red.events_every_s=0.5", "blue=do_nothing",
            "episode_length=8", "clock=lockstep", "display=plain", "run_dir=out", timeout=240,
        )  # fmt: skip
    assert proc.returncode in (0, 1), proc.stdout + proc.stderr  # 1: the pre-game's program for a stranger
    rec = json.loads((tmp_path / "out" / "episodes.jsonl").read_text())
    assert rec["status"] == "ok" and rec["conditions"].get("clock.mode") == "lockstep"
    assert "no answer" not in "\n".join(rec["problems"]["red"])
    # 16 planned; 13 seen once in a quiet CI run (not explained yet: the stop 59 note); the real clock gives ~9
    assert Slow.calls.count("/events") >= 12, Slow.calls
