"""`pillagerbench llm-ping [llm=PRESET] [llm.key=value ...]`: one short request, to check a provider.

Prints the answer, latency and token counts and exits 0, or prints the provider's error to
stderr and exits 1. Neither cache nor ledger is used: the request always reaches the provider.
"""

from __future__ import annotations

import asyncio
import sys

from pillagerbench.config import load_config
from pillagerbench.config_schema import LLMConfig, check, problems

from .client import LLMClient
from .errors import LLMError

PROMPT = "This is a connectivity check. Reply with the single word: pong"


async def _ping(cfg) -> int:
    s = None
    try:
        client = LLMClient.from_config(cfg.llm)
        s = client.settings
        async with client:
            answer = await client.complete(PROMPT, role="ping")
    except LLMError as exc:
        where = f"{s.provider} model {s.model} at {s.base_url}" if s else f"{cfg.llm.provider}"
        print(f"llm-ping: {where}: {type(exc).__name__}: {exc.detail}", file=sys.stderr)
        return 1
    print(f"provider: {s.provider}  model: {answer.model}  base_url: {s.base_url}")
    print(f"answer: {answer.text!r}")
    print(f"latency: {answer.latency_s:.3f} s  retries: {answer.retries}  finish_reason: {answer.finish_reason}")
    print(f"tokens: input {answer.input_tokens}  output {answer.output_tokens}")
    return 0


def main(argv: list[str]) -> int:
    cfg = load_config(argv)
    check(problems(LLMConfig, cfg.llm, "llm"))
    return asyncio.run(_ping(cfg))
