"""A remote team in Python with only the standard library: a small HTTP server speaking the
benchmark's remote-team protocol (docs/remote-teams.md). It harvests in Mushroom War.

    python3 examples/remote_team.py 8800 &
    pillagerbench run red=remote red.url=http://127.0.0.1:8800 blue=passive
"""

from __future__ import annotations

import json
import sys
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

BLOCKS = {"red": "red_mushroom_block", "blue": "brown_mushroom_block"}


def programs(pregame: dict) -> dict:
    """One JavaScript program per player, from what the pre-game message tells."""
    side = pregame["side"]
    block = BLOCKS.get(side["key"])
    out = {}
    for player in side["players"]:
        if pregame["scenario"]["key"] == "mushroom_war" and block:
            out[player["name"]] = f"while (true) {{ await mineBlock(bot, '{block}', 4); await bot.waitForTicks(10) }}"
        else:
            out[player["name"]] = "bot.chat('I only know Mushroom War')"
    return out


class Team(BaseHTTPRequestHandler):
    def answer(self, body: dict) -> None:
        data = json.dumps(body).encode()
        self.send_response(200)
        self.send_header("Content-Type", "application/json")
        self.send_header("Content-Length", str(len(data)))
        self.end_headers()
        self.wfile.write(data)

    def do_GET(self) -> None:
        self.answer({"protocol": 1, "name": "python-harvesters"})

    def do_POST(self) -> None:
        message = json.loads(self.rfile.read(int(self.headers["Content-Length"])))
        if self.path == "/pregame":
            self.answer({"programs": programs(message)})
        else:  # /events (keep the programs) and /postgame
            self.answer({})

    def log_message(self, *args) -> None:  # quiet
        pass


if __name__ == "__main__":
    server = ThreadingHTTPServer(("127.0.0.1", int(sys.argv[1]) if len(sys.argv) > 1 else 8800), Team)
    print(f"remote team on http://127.0.0.1:{server.server_address[1]}", flush=True)
    server.serve_forever()
