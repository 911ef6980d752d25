"""Fixtures for team tests: a fake OpenAI-compatible LLM server on loopback, LLM clients on it, and
a helper playing real episodes (real arena server, real bots, the Match class)."""

from __future__ import annotations

from pathlib import Path

from pillagerbench.config.schema import ClockConfig
from pillagerbench.match import Match
from pillagerbench.scenarios import make_scenario
from pillagerbench.server import ArenaServer
from pillagerbench.teams import make_team
from tests.support.llm import fake_llm, llm_client_fixture  # noqa: F401 - fixtures
from tests.support.server_clock import clock_of

llm_client = llm_client_fixture()


async def play_series(
    scenario_key: str,
    red,
    blue,
    run_dir: Path,
    *,
    episodes: int = 1,
    length: float = 20,
    llms: dict | None = None,
    seed: int = 1,
    clock: str | ClockConfig = "real",
    idle_limit_s: float | None = None,
    **match_options,
):
    """Play `episodes` episodes on a fresh server (on `clock`: a mode, or a whole ClockConfig); red/blue are
    team names or Team objects; `match_options` go to Match (scoring=, protocol=)."""
    config = clock_of(clock) if isinstance(clock, str) else clock
    sc = make_scenario(scenario_key, crop_growth_chance=0.3 if scenario_key == "dash_and_dine" else 0.0)
    teams = {side: make_team(t, sc.key) if isinstance(t, str) else t for side, t in (("red", red), ("blue", blue))}
    async with ArenaServer(log_path=run_dir / "server.log", clock=config.mode, idle_limit_s=idle_limit_s) as server:
        match = Match(
            server,
            sc,
            teams,
            run_dir,
            episode_length=length,
            seed=seed,
            llms=llms or {},
            clock=config,
            **match_options,
        )
        try:
            await match.setup()
            return [await match.play_episode(e) for e in range(episodes)]
        finally:
            await match.close()
