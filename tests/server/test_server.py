"""The arena server process and its control channel: start, bad input, death."""

from __future__ import annotations

import asyncio
import json
import os
import signal
import subprocess
import time

import pytest

from pillagerbench.server import ArenaServer, ControlError
from pillagerbench.server.control import ChannelClosed
from pillagerbench.server.process import exit_code


async def test_ready_with_flat_world_and_log(arena):
    assert arena.port and arena.port > 0
    assert arena.log_path.exists()
    assert (await arena.get_block(pos=[5, 3, 5]))["name"] == "grass_block"
    assert (await arena.get_block(pos=[5, 2, 5]))["name"] == "dirt"
    assert (await arena.get_block(pos=[5, 0, 5]))["name"] == "bedrock"
    assert (await arena.get_block(pos=[5, 4, 5]))["name"] == "air"


@pytest.mark.parametrize(
    "op,args,message",
    [
        ("set_block", {"pos": [0, 4, 0], "block": "chst"}, "unknown block 'chst'"),
        ("set_block", {"pos": [0, 300, 0], "block": "stone"}, "out of range"),
        ("set_block", {"pos": [0, "a", 0], "block": "stone"}, "must be [x, y, z] numbers"),
        ("set_block", {"pos": [0, 4, 0], "block": "wheat", "properties": {"age": 12}}, "bad value 12 for wheat.age"),
        ("give", {"player": "nobody", "item": "bread"}, 'no player named "nobody"'),
        ("fill", {"from": [0, 4, 0], "to": [100, 100, 100], "block": "stone"}, "larger than"),
        ("set_chest", {"pos": [0, 4, 0], "items": {"brea": 3}}, "unknown item 'brea'"),
        ("summon", {"mob": "dragon", "pos": [0, 4, 0]}, "unknown mob 'dragon'"),
        ("tick_rate", {"tps": 0}, "tps must be between"),
        ("no_such_op", {}, 'unknown op "no_such_op"'),
        ("toString", {}, 'unknown op "toString"'),
        ("set_block", {"pos": [0, 4, 0], "block": "stone", "colour": "red"}, 'op set_block has no argument "colour"'),
        ("get_block", {}, 'op get_block needs the argument "pos"'),
        ("give", {"player": "nobody", "item": 5}, "op give: argument item must be a string, got 5"),
        ("give", {"player": "nobody", "item": "bread", "count": 1.5}, "argument count must be an integer, got 1.5"),
        ("replay_frame", {"start": "yes"}, 'argument start must be a boolean, got "yes"'),
    ],
)
async def test_bad_requests_get_an_error_naming_the_problem(arena, op, args, message):
    with pytest.raises(ControlError, match=None) as info:
        await arena.request(op, **args)
    assert message in str(info.value)
    assert await arena.ping() == "pong"  # still running


async def test_malformed_lines_get_an_error_reply(arena):
    arena.control._writer.write(b'this is not json\n{"op": 5}\n[1, 2]\n')
    await arena.control._writer.drain()
    assert await arena.ping() == "pong"
    errors = [m["error"] for m in arena.control.unmatched[-3:]]
    assert "malformed control message (not JSON)" in errors[0]
    assert 'string "op"' in errors[1]
    assert 'string "op"' in errors[2]


async def test_unknown_item_in_give_names_item(arena, bots):
    with pytest.raises(ControlError, match="unknown item 'diamnd'"):
        await arena.give(player="alice", item="diamnd", count=1)


async def test_death_of_the_server_is_reported_clearly(tmp_path):
    server = ArenaServer(log_path=tmp_path / "server.log")
    await server.start()
    assert server.ready_seconds is not None
    os.killpg(server.process.pid, signal.SIGKILL)
    with pytest.raises(ChannelClosed, match="exit code"):
        for _ in range(50):
            await server.ping()
            await asyncio.sleep(0.1)
    await server.stop()


async def test_a_killed_server_is_not_alive_and_is_left_for_asyncio_to_collect(tmp_path):
    """Killed from outside (kill anywhere, issue 55 item 6): dead as soon as its channel closes, so the
    match starts a fresh one, and its exit status is asyncio's to collect, -9 (reaped behind asyncio's
    back, its returncode stayed None: the server read as alive and every later episode failed)."""
    server = ArenaServer(log_path=tmp_path / "server.log")
    await server.start()
    proc = server.process
    os.kill(proc.pid, signal.SIGKILL)
    with pytest.raises(ChannelClosed, match="exit code"):
        for _ in range(50):
            await server.ping()
            await asyncio.sleep(0.1)
    assert not server.alive
    assert await asyncio.wait_for(proc.wait(), 10) == -9
    await server.stop()


async def test_a_server_whose_parent_went_without_reading_stops(tmp_path):
    """A parent killed with the server's replies unread (as in a run killed while its server started): the
    server's channel fails (ECONNRESET, or EPIPE on its next write) with no end of stream; it stops all the
    same, never an orphan listening on its port."""
    server = ArenaServer(log_path=tmp_path / "server.log")
    await server.start()
    proc, control = server.process, server.control
    control._writer.transport.pause_reading()  # nothing reads the replies from here on: they stay in the socket
    for i in range(20):
        control._writer.write(json.dumps({"id": 10_000 + i, "op": "ping"}).encode() + b"\n")
    await control._writer.drain()
    await asyncio.sleep(1)  # the replies are in our socket, unread
    control._writer.transport.abort()
    assert await asyncio.wait_for(proc.wait(), 15) == 0
    await server.stop()


def test_an_exit_code_is_read_without_reaping_the_process():
    child = subprocess.Popen(["sleep", "30"])
    child.kill()
    deadline = time.monotonic() + 10
    while exit_code(child.pid) is None and time.monotonic() < deadline:
        time.sleep(0.01)
    assert exit_code(child.pid) == exit_code(child.pid) == -9  # read twice: still there
    assert child.wait(timeout=5) == -9  # and its parent still collects it


async def test_clean_shutdown(tmp_path):
    server = ArenaServer(log_path=tmp_path / "server.log")
    await server.start()
    proc = server.process
    await server.stop()
    assert proc.returncode is not None
    assert not server.alive


async def test_request_to_a_peer_gone_before_the_read_loop_noticed_names_why():
    """A write that fails because the server just died is a ChannelClosed with the death reason,
    not a bare ConnectionResetError (seen under load: the kill raced the reader)."""
    import socket

    from pillagerbench.server.control import ControlChannel

    ours, theirs = socket.socketpair()
    theirs.close()
    reader, writer = await asyncio.open_connection(sock=ours)
    channel = ControlChannel(reader, writer, on_close=lambda: "arena server process ended (exit code -9)")
    with pytest.raises(ChannelClosed, match="exit code -9"):
        for _ in range(50):  # the first writes may still be buffered by the kernel
            await channel.request("ping", timeout=1)
    with pytest.raises(ChannelClosed):  # it closed before the server said it was ready
        await channel.ready
    await channel.close()
