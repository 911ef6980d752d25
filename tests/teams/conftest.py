"""Fixtures for team tests: a fake OpenAI-compatible LLM server on loopback, LLM clients on it, and
a helper playing real episodes (real arena server, real bots, the Match class)."""

from __future__ import annotations

from pathlib import Path

import pytest

from pillagerbench.arena import ArenaServer
from pillagerbench.config import load_config
from pillagerbench.llm import LLMClient
from pillagerbench.llm.fake_server import FakeLLMServer
from pillagerbench.match import Match
from pillagerbench.scenarios import make_scenario
from pillagerbench.teams import make_team


@pytest.fixture
def fake_llm():
    with FakeLLMServer() as server:
        yield server


@pytest.fixture
async def llm_client(fake_llm, tmp_path):
    """llm_client(team="red") -> an LLMClient on the fake server (ledger in tmp_path/llm)."""
    made: list[LLMClient] = []

    def make(team: str = "red", *overrides: str) -> LLMClient:
        cfg = load_config(["llm=fake", f"llm.base_url={fake_llm.url}", "llm.timeout=10", *overrides])
        client = LLMClient.from_config(cfg, team=team, run_dir=tmp_path / "llm")
        made.append(client)
        return client

    yield make
    for client in made:
        await client.aclose()


async def play_series(scenario_key: str, red, blue, run_dir: Path, *, episodes: int = 1, length: float = 20,
                      llms: dict | None = None, seed: int = 1):
    """Play `episodes` episodes on a fresh server; red/blue are team names or Team objects."""
    sc = make_scenario(scenario_key, crop_growth_chance=0.3 if scenario_key == "dash_and_dine" else 0.0)
    teams = {side: make_team(t, sc.key) if isinstance(t, str) else t for side, t in (("red", red), ("blue", blue))}
    async with ArenaServer(log_path=run_dir / "server.log") as server:
        match = Match(server, sc, teams, run_dir, episode_length=length, seed=seed, llms=llms or {})
        try:
            await match.setup()
            return [await match.play_episode(e) for e in range(episodes)]
        finally:
            await match.close()
