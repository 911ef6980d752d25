from __future__ import annotations

import random

import pytest_asyncio

from pillagerbench.server import ArenaServer


@pytest_asyncio.fixture(scope="module", loop_scope="session")
async def server(tmp_path_factory):
    s = ArenaServer(log_path=tmp_path_factory.mktemp("scenario-server") / "server.log")
    await s.start()
    yield s
    await s.stop()


class Always(random.Random):
    """A random source whose every draw is `value` (0.0: every chance happens; 0.99: none does)."""

    def __init__(self, value: float):
        super().__init__(0)
        self.value = value

    def random(self) -> float:
        return self.value
