"""Overhead of our LLM client against the fake provider, printed as JSON.

    python benchmarks/llm_overhead.py [--calls 300]

- raw_ms: one POST /v1/chat/completions with a bare httpx2.AsyncClient (keep-alive), the same
  transport the openai SDK uses; raw_stdlib_ms: the same with http.client, for reference.
- client_ms: LLMClient.complete (SDK, our retry loop, request building, ledger line, cache key).
- overhead_ms = client_ms - raw_ms (target <= 2 ms).
- cache_hit_ms: LLMClient.complete in replay mode, every call a hit (target <= 1 ms).
The fake server runs in its own process so its work is not counted in the client's.
Figures are medians over `--calls` calls after a warm-up; means are printed too.
"""

from __future__ import annotations

import argparse
import asyncio
import http.client
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from urllib.parse import urlparse

import httpx2

from pillagerbench.config.compose import load_config
from pillagerbench.llm import Ledger, LLMCache, LLMClient

MESSAGES = [
    {"role": "system", "content": "You are a Minecraft agent."},
    {"role": "user", "content": "Next action? Reply with one line of code."},
]


def stats(samples: list[float]) -> dict:
    return {"median": round(statistics.median(samples) * 1000, 3), "mean": round(statistics.mean(samples) * 1000, 3)}


async def timed(n: int, call) -> list[float]:
    for _ in range(20):  # warm-up: connections, imports, caches
        await call(-1)
    out = []
    for i in range(n):
        t0 = time.perf_counter()
        await call(i)
        out.append(time.perf_counter() - t0)
    return out


async def run(n: int, url: str) -> dict:
    body = {"model": "fake-model", "messages": MESSAGES, "temperature": 0.3, "max_tokens": 512}
    async with httpx2.AsyncClient(base_url=url, timeout=10) as raw:

        async def raw_call(i: int) -> None:
            r = await raw.post("/chat/completions", json=body)
            json.loads(r.content)

        raw_t = await timed(n, raw_call)

    parts = urlparse(url)
    conn = http.client.HTTPConnection(parts.hostname, parts.port, timeout=10)

    async def stdlib_call(i: int) -> None:
        conn.request("POST", parts.path + "/chat/completions", json.dumps(body), {"Content-Type": "application/json"})
        json.loads(conn.getresponse().read())

    stdlib_t = await timed(n, stdlib_call)
    conn.close()

    with tempfile.TemporaryDirectory() as tmp:
        cfg = load_config(["llm=fake", f"llm.base_url={url}"])
        cache_dir = Path(tmp) / "cache"
        async with LLMClient.from_config(cfg, team="red", run_dir=Path(tmp) / "run1") as client:
            client_t = await timed(n, lambda i: client.complete(MESSAGES, role="action"))
        # fill a cache with n+20 distinct requests, then replay them in a new run
        prompts = [MESSAGES[:1] + [{"role": "user", "content": f"Next action #{i}?"}] for i in range(-1, n)]
        async with LLMClient.from_config(cfg, team="red", cache=LLMCache(cache_dir, "write")) as writer:
            for p in prompts:
                await writer.complete(p, role="action")
        ledger = Ledger(Path(tmp) / "run2")
        async with LLMClient.from_config(cfg, team="red", ledger=ledger, cache=LLMCache(cache_dir, "replay")) as replay:
            await replay.complete(prompts[0], role="action")  # warm-up (each prompt hits once)
            hit_t = []
            for p in prompts[1:]:
                t0 = time.perf_counter()
                await replay.complete(p, role="action")
                hit_t.append(time.perf_counter() - t0)

    raw_s, client_s = stats(raw_t), stats(client_t)
    return {
        "calls": n,
        "raw_ms": raw_s,
        "raw_stdlib_ms": stats(stdlib_t),
        "client_ms": client_s,
        "overhead_ms": {k: round(client_s[k] - raw_s[k], 3) for k in ("median", "mean")},
        "overhead_target_ms": 2.0,
        "cache_hit_ms": stats(hit_t),
        "cache_hit_target_ms": 1.0,
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=300)
    args = parser.parse_args()
    server = subprocess.Popen(
        [sys.executable, "-m", "pillagerbench.llm.fake_server", "--port", "0"], stdout=subprocess.PIPE, text=True
    )
    try:
        url = server.stdout.readline().strip()
        result = asyncio.run(run(args.calls, url))
    finally:
        server.terminate()
        server.wait(timeout=10)
    print(json.dumps(result, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
