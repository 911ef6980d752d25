"""The address people's Minecraft clients join at (`humans.client=minecraft`, docs/people.md): `LoginGate`
reads what a client sends before the arena server does, the handshake and the login's name (the
protocol's first two packets, uncompressed and unencrypted in offline mode), admits a 1.16.5 client under
the name of a player people play here and refuses anyone else with the protocol's own login disconnect
(the client shows the line); an admitted client's bytes pass both ways untouched, so the server's checks
hold for it as for any player."""

from __future__ import annotations

import asyncio
import contextlib
import json
from collections.abc import Callable, Sequence

from pillagerbench.config.people import name_problem
from pillagerbench.server.process import MC_VERSION

PROTOCOL = 754  # the protocol version of Minecraft Java MC_VERSION (1.16.5), the server's
MAX_PACKET = 2**16  # a handshake or a login start is far smaller


class Refusal(Exception):
    """Why the gate refuses a login: one line, shown by the client."""


def varint(value: int) -> bytes:
    out = bytearray()
    value &= 0xFFFFFFFF
    while True:
        byte, value = value & 0x7F, value >> 7
        out.append(byte | (0x80 if value else 0))
        if not value:
            return bytes(out)


async def _read_varint(reader: asyncio.StreamReader, raw: bytearray) -> int:
    value = 0
    for shift in range(0, 35, 7):
        byte = (await reader.readexactly(1))[0]
        raw.append(byte)
        value |= (byte & 0x7F) << shift
        if not byte & 0x80:
            return value
    raise Refusal("a malformed packet")


def _take_varint(data: bytes, at: int) -> tuple[int, int]:
    value = 0
    for shift in range(0, 35, 7):
        if at >= len(data):
            break
        byte = data[at]
        at += 1
        value |= (byte & 0x7F) << shift
        if not byte & 0x80:
            return value, at
    raise Refusal("a malformed packet")


def _take_string(data: bytes, at: int) -> tuple[str, int]:
    size, at = _take_varint(data, at)
    if at + size > len(data):
        raise Refusal("a malformed packet")
    return data[at : at + size].decode("utf-8", errors="replace"), at + size


async def _packet(reader: asyncio.StreamReader, raw: bytearray) -> bytes:
    """One uncompressed packet (its id and fields); its bytes as sent are added to `raw`."""
    size = await _read_varint(reader, raw)
    if not 0 < size <= MAX_PACKET:
        raise Refusal("a malformed packet")
    body = await reader.readexactly(size)
    raw.extend(body)
    return body


def handshake(body: bytes) -> tuple[int, int]:
    """(protocol version, next state: 1 status, 2 login) of a handshake packet."""
    packet, at = _take_varint(body, 0)
    if packet != 0:
        raise Refusal("not a Minecraft Java client")
    version, at = _take_varint(body, at)
    _, at = _take_string(body, at)  # the address the client was given
    state, _ = _take_varint(body, at + 2)  # after the port (2 bytes)
    return version, state


def login_name(body: bytes) -> str:
    packet, at = _take_varint(body, 0)
    if packet != 0:
        raise Refusal("not a login")
    return _take_string(body, at)[0]


def disconnect(reason: str) -> bytes:
    """The login state's disconnect packet: the client shows `reason`."""
    text = json.dumps({"text": reason}).encode()
    body = varint(0) + varint(len(text)) + text
    return varint(len(body)) + body


class LoginGate:
    """The address people's clients join at: admits the names in `names` (the players people play here)
    and passes their bytes to the arena server at `target()` (host, port: a restarted server's new port);
    any other name is refused at login."""

    def __init__(self, names: Sequence[str], target: Callable[[], tuple[str, int]], host: str, port: int = 0):
        self.names, self.target, self.host, self.port = list(names), target, host, port
        self.refused: list[tuple[str, str]] = []  # (name, why): each login refused
        self._server: asyncio.Server | None = None
        self._pipes: set[asyncio.Task] = set()

    async def start(self) -> str:
        """Listen; the address (host:port) a person's client joins."""
        self._server = await asyncio.start_server(self._serve, self.host, self.port)
        self.port = self._server.sockets[0].getsockname()[1]
        return f"{self.host}:{self.port}"

    async def stop(self, grace_s: float = 2.0) -> None:
        """No more logins; each client's pipe ends when the arena server closes its side (what the server said
        last, the whistle, still reaches the client), or is cut after `grace_s`."""
        if self._server is not None:
            self._server.close()
            if self._pipes:
                await asyncio.wait(list(self._pipes), timeout=grace_s)
            for task in list(self._pipes):
                task.cancel()
            await asyncio.gather(*self._pipes, return_exceptions=True)
            self._server = None

    def admit(self, version: int, name: str) -> None:
        """Refusal unless a 1.16.5 client logs in under the name of a player people play here."""
        if version != PROTOCOL:
            raise Refusal(
                f"join with Minecraft Java {MC_VERSION} (protocol {PROTOCOL}); this client speaks protocol {version}"
            )
        problem = name_problem(name)
        if problem:
            raise Refusal(problem)
        if name not in self.names:
            raise Refusal(f"{name!r} does not play here: join as {' or '.join(self.names)} (the players people play)")

    async def _serve(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        task = asyncio.current_task()
        if task is not None:
            self._pipes.add(task)
        raw = bytearray()
        try:
            version, state = handshake(await asyncio.wait_for(_packet(reader, raw), 10))
            if state == 2:
                name = login_name(await asyncio.wait_for(_packet(reader, raw), 10))
                try:
                    self.admit(version, name)
                except Refusal as exc:
                    self.refused.append((name, str(exc)))
                    writer.write(disconnect(str(exc)))
                    await writer.drain()
                    return
            await self._pass(bytes(raw), reader, writer)
        except (Refusal, asyncio.IncompleteReadError, asyncio.TimeoutError, ConnectionError, OSError):
            return
        finally:
            writer.close()
            if task is not None:
                self._pipes.discard(task)

    async def _pass(self, first: bytes, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        """Every byte both ways between the client and the server, the ones read so far first."""
        up_reader, up_writer = await asyncio.open_connection(*self.target())
        up_writer.write(first)
        try:
            await asyncio.gather(_copy(reader, up_writer), _copy(up_reader, writer))
        finally:
            up_writer.close()


async def _copy(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
    try:
        while data := await reader.read(65536):
            writer.write(data)
            await writer.drain()
    except (ConnectionError, OSError):
        pass
    finally:
        with contextlib.suppress(Exception):
            writer.write_eof()
