"""A person plays a real match from a Minecraft client (`humans.client=minecraft`, people/client.py): no bot is
launched for the person's player; the run prints the address and the name to join with. There is no Minecraft
Java client here, so a plain mineflayer client (not our bot: no sandbox, no control channel, no wrapper; the
same protocol as the Java client's) stands in: it joins under the player's name, walks and digs, leaves and
comes back; another name is refused at login. The server's own records show the player as any player's:
the dug block in world_events, its moves in the replay's frames, the episode's record (the entrant
human:Ryn, a score every second)."""

from __future__ import annotations

import asyncio
import json
import os
import re
import subprocess
import sys
from pathlib import Path

from pillagerbench.host.node import node_binary, node_env
from pillagerbench.people.gate import LoginGate
from tests.support.people import frames

EPISODE_S = 15  # the client's walk, dig, leave and rejoin take ~7 s, more under load; the whistle after

# A plain mineflayer client. mode "refused": log in and print the kick; mode "play": join, wait for the game,
# walk forward a second, dig the block underfoot, leave, join again and print where the server put it back.
CLIENT = r"""
const mineflayer = require('mineflayer')
const { host, port, name, mode } = JSON.parse(process.argv[1])
const out = (what) => console.log(JSON.stringify(what))
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms))
function join () {
  const bot = mineflayer.createBot({ host, port, username: name, version: '1.16.5', auth: 'offline' })
  bot.on('kicked', (reason) => { out({ kicked: String(reason) }); if (mode === 'refused') process.exit(0) })
  bot.on('error', (err) => out({ error: String(err) }))
  return bot
}
const spawned = (bot) => new Promise((resolve) => bot.once('spawn', resolve))
const heard = (bot, text) => new Promise((resolve) => bot.on('messagestr', (m) => { if (m.includes(text)) resolve(m) }))
const at = (bot) => { const p = bot.entity.position; return [p.x, p.y, p.z] }
async function play () {
  let bot = join()
  await spawned(bot)
  out({ joined: at(bot) })
  await heard(bot, 'the game is on')
  await sleep(500) // the reset's teleport has come
  out({ start: at(bot) })
  bot.setControlState('forward', true)
  await sleep(1000)
  bot.setControlState('forward', false)
  await sleep(300)
  const below = bot.blockAt(bot.entity.position.offset(0, -1, 0))
  await bot.dig(below)
  out({ dug: below.name, at: at(bot) })
  await sleep(300)
  const left = at(bot)
  bot.quit()
  await sleep(1000)
  bot = join()
  const whistle = heard(bot, 'the whistle') // from the rejoin on (told only to people in the world)
  await spawned(bot)
  await sleep(2500) // the next second's look puts the player back
  out({ left, back: at(bot) })
  out({ whistle: await whistle })
  bot.quit()
}
if (mode === 'refused') join()
else play().then(() => process.exit(0), (err) => { out({ error: String(err) }); process.exit(1) })
"""


def _client(address: str, name: str, mode: str) -> subprocess.Popen:
    host, port = address.rsplit(":", 1)
    args = json.dumps({"host": host, "port": int(port), "name": name, "mode": mode})
    return subprocess.Popen(
        [str(node_binary()), "-e", CLIENT, args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=node_env(),
    )


def _lines(proc: subprocess.Popen, timeout: float) -> list[dict]:
    out, err = proc.communicate(timeout=timeout)
    assert proc.returncode == 0, err[-2000:]
    return [json.loads(line) for line in out.splitlines() if line.startswith("{")]


def _address(proc: subprocess.Popen) -> str:
    assert proc.stdout is not None
    for line in proc.stdout:
        found = re.match(r"people: join with a Minecraft Java 1\.16\.5 client at (\S+) as Ryn \(red\)$", line.strip())
        if found:
            return found.group(1)
    raise AssertionError("no address printed")


def _match(run_dir: Path) -> subprocess.Popen:
    cmd = [sys.executable, "-m", "pillagerbench.cli", "run", "red=do_nothing", "red.humans=[Ryn]"]
    cmd += ["humans.client=minecraft", "blue=do_nothing", f"episode_length={EPISODE_S}", f"run_dir={run_dir}"]
    cmd += ["display=plain", "humans.ready_timeout_s=60", "retries=0"]
    return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=os.environ.copy())


def test_a_person_plays_from_a_minecraft_client(tmp_path: Path):
    run_dir = tmp_path / "run"
    proc = _match(run_dir)
    try:
        address = _address(proc)
        for name in ("mallory", "Raze"):  # a stranger, and an agent's player: refused at login
            kicked = _lines(_client(address, name, "refused"), 30)
            assert kicked and "does not play here: join as Ryn" in kicked[0]["kicked"], kicked
        lines = _lines(_client(address, "Ryn", "play"), 60)
        assert proc.wait(timeout=60) == 0
    finally:
        proc.kill()
        rest = proc.stdout.read() if proc.stdout else ""
    got = {k: v for line in lines for k, v in line.items()}
    assert "error" not in got, (got, rest)
    assert got["start"] == [-6.5, 4, -9.5]  # Ryn's spawn: the reset placed the person's player
    assert got["dug"] == "grass_block"
    left, back = got["left"], got["back"]
    assert abs(back[0] - left[0]) < 1 and abs(back[2] - left[2]) < 1  # back where it was when it left
    assert "red 0" in got.get("whistle", ""), (got, rest)
    episode = json.loads((run_dir / "episode_000" / "episode.json").read_text())
    assert episode["status"] == "ok" and episode["red_entrant"]["label"] == "do_nothing+human:Ryn", episode
    timeline = json.loads((run_dir / "episode_000" / "timeline.json").read_text())
    assert len(timeline) >= EPISODE_S
    events = [json.loads(line) for line in (run_dir / "episode_000" / "world_events.jsonl").read_text().splitlines()]
    dug = [e for e in events if e["event"] == "block_dug" and e["player"] == "Ryn"]
    assert dug and dug[0]["block"] == "grass_block"
    assert any(e["event"] == "player_left" and e["player"] == "Ryn" for e in events)
    moves = {(round(p[1], 1), round(p[3], 1)) for p in frames(run_dir, "Ryn")}
    assert len(moves) > 1  # the frames show the player walking
    assert not (run_dir / "episode_000" / "events" / "Ryn.jsonl").exists()  # no bot: no runs of its own


def test_the_gate_refuses_another_version_and_a_bad_name():
    gate = LoginGate(["Ryn"], lambda: ("127.0.0.1", 1), "127.0.0.1")
    for version, name, why in [(340, "Ryn", "protocol 340"), (754, "no way", "not a player name")]:
        try:
            gate.admit(version, name)
        except Exception as exc:  # noqa: BLE001 - the refusal's line
            assert why in str(exc)
        else:
            raise AssertionError("admitted")
    gate.admit(754, "Ryn")
    asyncio.run(gate.stop())
