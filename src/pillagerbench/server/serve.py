"""`pillagerbench server`: start an arena server for people to watch with a real 1.16.5 client.

    pillagerbench server server.port=25565 server.operators=[Steve]
    pillagerbench server watch=8080          # and a live 3D view in the browser at http://127.0.0.1:8080/

Runs until Ctrl-C. Players named in `server.operators` may use chat commands such as /fill and /tp;
everyone else (every agent) is refused.
"""

from __future__ import annotations

import asyncio

from pillagerbench.config.validate import load_server
from pillagerbench.server.process import MC_VERSION, ArenaServer


async def _serve(server: ArenaServer) -> None:
    await server.start()
    print(f"arena server (Minecraft {MC_VERSION}, offline mode) ready in {server.ready_seconds:.2f} s")
    print(f"connect a Minecraft {MC_VERSION} client to {server.host}:{server.port}")
    print(f"server log: {server.log_path}")
    if server.watch_url:
        print(f"live view: {server.watch_url} (a browser; the view is not a player)")
    print("Ctrl-C stops it.", flush=True)
    try:
        while server.alive:
            await asyncio.sleep(0.5)
        print(f"arena server stopped by itself:\n{server.log_tail()}")
    finally:
        await server.stop()


def main(argv: list[str]) -> int:
    config, watch = load_server(argv)
    server = ArenaServer.from_config(config, watch=watch)
    try:
        asyncio.run(_serve(server))
    except KeyboardInterrupt:
        print("\nstopped")
    return 0
