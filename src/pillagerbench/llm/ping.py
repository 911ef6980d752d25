"""`pillagerbench llm-ping [llm=PRESET] [llm.key=value ...]`: one short request, to check a provider.

Prints the answer, latency and token counts and exits 0, or prints the provider's error to
stderr and exits 1 (the provider is unreachable, refused the key or failed: what the check is for).
A mistake in the settings (unknown preset, a bad value, the key's variable not set) is a user error
like any other command's: one line, exit 2. Neither cache nor ledger is used: the request always
reaches the provider.
"""

from __future__ import annotations

import asyncio
import sys

from pillagerbench.config.compose import ConfigError, load_config
from pillagerbench.config.schema import LLMConfig, check, problems

from .client import LLMClient
from .errors import LLMConfigError, LLMError

PROMPT = "This is a connectivity check. Reply with the single word: pong"


async def _ping(cfg) -> int:
    s = None
    try:
        client = LLMClient.from_config(cfg.llm)
        s = client.settings
        async with client:
            answer = await client.complete(PROMPT, role="ping")
    except LLMConfigError as exc:  # the user's settings (cli.main prints it: exit 2)
        raise ConfigError(f"{cfg.llm.provider}: {exc.detail}") from None
    except LLMError as exc:  # the provider's answer, or none
        where = f"{s.provider} model {s.model} at {s.base_url}" if s else f"{cfg.llm.provider}"
        print(f"pillagerbench llm-ping: {where}: {type(exc).__name__}: {exc.detail}", file=sys.stderr)
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
