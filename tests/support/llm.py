"""Shared test fixtures for LLM teams: the fake OpenAI-compatible server (`pillagerbench.llm.fake_server`)
on loopback, and LLM clients on it. Import `fake_llm` and build `llm_client` with `llm_client_fixture`."""

from __future__ import annotations

import pytest

from pillagerbench.config.compose import load_config
from pillagerbench.llm import LLMClient
from pillagerbench.llm.fake_server import FakeLLMServer


@pytest.fixture
def fake_llm():
    with FakeLLMServer() as server:
        yield server


def llm_client_fixture(*default_overrides: str):
    """A fixture: llm_client(team="red", *overrides) -> an LLMClient on the fake server (ledger in tmp_path/llm)."""

    @pytest.fixture
    async def llm_client(fake_llm, tmp_path):
        made: list[LLMClient] = []

        def make(team: str = "red", *overrides: str) -> LLMClient:
            cfg = load_config(
                ["llm=fake", f"llm.base_url={fake_llm.url}", "llm.timeout=10", *default_overrides, *overrides]
            )
            client = LLMClient.from_config(cfg, team=team, run_dir=tmp_path / "llm")
            made.append(client)
            return client

        yield make
        for client in made:
            await client.aclose()

    return llm_client
