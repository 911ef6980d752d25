"""Opt-in: one real request to a local model server (scripts/local_llm.sh serve).

Runs only with PILLAGERBENCH_LOCAL_LLM_URL set (e.g. http://127.0.0.1:8080/v1) and reachable.
"""

import os
import urllib.request

import pytest

from pillagerbench.config.compose import load_config
from pillagerbench.llm import LLMClient, read_ledger

URL = os.environ.get("PILLAGERBENCH_LOCAL_LLM_URL")


def reachable(url: str | None) -> bool:
    if not url:
        return False
    try:
        with urllib.request.urlopen(url.rstrip("/") + "/models", timeout=2):
            return True
    except OSError:
        return False


@pytest.mark.local_llm
@pytest.mark.skipif(not reachable(URL), reason="PILLAGERBENCH_LOCAL_LLM_URL not set or not reachable")
async def test_real_local_model(tmp_path):
    cfg = load_config(["llm=llamacpp", f"llm.base_url={URL}", "llm.max_tokens=32", "llm.temperature=0"])
    async with LLMClient.from_config(cfg, team="red", run_dir=tmp_path) as client:
        answer = await client.complete("Say hello in one word.", role="action")
    assert answer.text and answer.output_tokens and answer.output_tokens > 0
    [rec] = read_ledger(tmp_path)
    assert rec["error"] is None and rec["latency_s"] > 0 and rec["input_tokens"] > 0
