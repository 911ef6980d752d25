"""Fixtures for LLM tests: a real FakeLLMServer on loopback and clients pointed at it.

Other teams' tests can do the same with `from pillagerbench.llm.fake_server import FakeLLMServer,
Rule` and `load_config(["llm=fake", f"llm.base_url={server.url}"])`.
"""

from __future__ import annotations

import socket
from pathlib import Path

import pytest

from pillagerbench.config.compose import load_config
from pillagerbench.llm import LLMClient, read_ledger
from pillagerbench.llm.fake_server import FakeLLMServer


@pytest.fixture
def fake_llm():
    with FakeLLMServer() as server:
        yield server


def fake_config(url: str, *overrides: str):
    return load_config(["llm=fake", f"llm.base_url={url}", *overrides])


@pytest.fixture
async def make_client(fake_llm, tmp_path):
    """make_client(*overrides, team=..., run_dir=...) -> LLMClient on the fake server."""
    made: list[LLMClient] = []

    def make(*overrides: str, team: str | None = "red", run_dir: Path | None = None, url: str | None = None):
        cfg = fake_config(url or fake_llm.url, *overrides)
        client = LLMClient.from_config(cfg, team=team, run_dir=run_dir or tmp_path / "run")
        made.append(client)
        return client

    yield make
    for client in made:
        await client.aclose()


@pytest.fixture
def ledger_of(tmp_path):
    def records(run_dir: Path | None = None) -> list[dict]:
        return list(read_ledger(run_dir or tmp_path / "run"))

    return records


@pytest.fixture
def closed_port() -> int:
    """A loopback port where nothing listens (connection refused)."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]
