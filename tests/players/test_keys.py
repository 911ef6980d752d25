"""Keys stay with us (issue 37 item 8): a secret in the user's environment reaches neither the
server's nor a bot's process, nor agent code run in the sandbox."""

from __future__ import annotations

import json
import secrets
from pathlib import Path

from pillagerbench.host.node import NODE_ENV_ALLOWED
from pillagerbench.players import Player
from pillagerbench.players.events import errors
from pillagerbench.server import ArenaServer

# Routes agent code might take to the process's environment; each yields a string (what it reached
# or the error that stopped it), so the secret would show in the answer if any route led to it.
PROBES = r"""
// a property's name with its value if a string, else its type (no deep walk: that is test_sandbox's)
const described = (o, k) => { try { const v = o[k]; return k + '=' + (typeof v === 'string' ? v : typeof v) } catch (e) { return k } }
const tries = {
  process: () => process.env,
  globalProcess: () => globalThis.process.env,
  env: () => env,
  globalEnv: () => globalThis.env,
  thisConstructor: () => this.constructor.constructor('return process.env')(),
  botConstructor: () => bot.constructor.constructor('return process.env')(),
  chatConstructor: () => bot.chat.constructor('return process.env')(),
  vecConstructor: () => bot.entity.position.constructor.constructor('return process.env')(),
  sloppyThis: () => (function () { return this })().process.env,
  globals: () => Object.getOwnPropertyNames(globalThis).map(k => described(globalThis, k)),
  botProperties: () => Object.getOwnPropertyNames(bot).map(k => described(bot, k))
}
const out = {}
for (const [name, f] of Object.entries(tries)) {
  try { out[name] = JSON.stringify(f()) ?? 'undefined' } catch (e) { out[name] = 'refused: ' + e.name + ': ' + e.message }
}
bot.save(JSON.stringify(out))
"""


def _environ(pid: int) -> dict[str, str]:
    raw = Path(f"/proc/{pid}/environ").read_bytes().split(b"\0")
    return dict(item.decode().split("=", 1) for item in raw if b"=" in item)


async def test_a_secret_in_the_parents_environment_reaches_no_node_process_nor_agent_code(monkeypatch, tmp_path):
    secret = f"sk-test-secret-{secrets.token_hex(8)}"
    monkeypatch.setenv("OPENAI_API_KEY", secret)
    monkeypatch.setenv("PB_TEST_UNUSUAL_VARIABLE", "an unusual value")
    monkeypatch.setenv("TZ", "UTC")  # an allowed name: it does arrive
    async with ArenaServer(log_path=tmp_path / "server.log", crop_growth_chance=0.0) as server:
        player = Player("keys1", server.port, server=server, log_dir=tmp_path / "logs")
        await player.start()
        try:
            await player.reset(position=[0, 4, 0], inventory={})
            assert server.process is not None and player.bot.proc is not None
            for who, pid in (("server", server.process.pid), ("bot", player.bot.proc.pid)):
                env = _environ(pid)
                assert "NODE_PATH" in env and env.get("TZ") == "UTC", (who, sorted(env))  # the right process
                assert "OPENAI_API_KEY" not in env and "PB_TEST_UNUSUAL_VARIABLE" not in env, (who, sorted(env))
                assert secret not in "\0".join(env.values()), who
                exact = {n for n in NODE_ENV_ALLOWED if not n.endswith("*")} | {"NODE_PATH", "NODE_ENV"}
                prefixes = tuple(n[:-1] for n in NODE_ENV_ALLOWED if n.endswith("*"))
                assert all(k in exact or k.startswith(prefixes) for k in env), (who, sorted(env))
            events = await player.run(PROBES, timeout=60)
            assert errors(events) == [], errors(events)
            reached = json.loads(next(e[1]["onSave"] for e in events if e[0] == "onSave"))
        finally:
            await player.close()
    assert secret not in json.dumps(reached)
    assert reached["process"] == "refused: ReferenceError: process is not defined"
    assert reached["env"] == "refused: ReferenceError: env is not defined"
    assert reached["globalProcess"].startswith("refused: TypeError") and reached["globalEnv"] == "undefined"
    for route in ("thisConstructor", "botConstructor", "chatConstructor", "vecConstructor"):
        assert reached[route].startswith("refused: EvalError"), (route, reached[route])
