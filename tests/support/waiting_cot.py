"""A `cot` team on the fake provider whose every answer waits (20 ticks a player), against
do_nothing in short lockstep episodes: the series the outage and spoiled-replay tests play."""

from __future__ import annotations

from pillagerbench.llm.fake_server import FakeLLMServer

WAIT = "async function main(bot) {\n  await bot.waitForTicks(20)\n}"
ANSWER = "Plan: wait.\n" + "\n".join(f"Code for bot {i}:\n```javascript\n{WAIT}\n```" for i in range(2))


def overrides(fake: FakeLLMServer, episodes: int, *extra: str) -> list[str]:
    """The run's overrides: cot (red) on `fake`, no retries of a call, 6 s lockstep episodes."""
    return [
        "scenario=mushroom_war",
        "red=cot",
        "blue=do_nothing",
        "llm=fake",
        f"llm.base_url={fake.url}",
        "llm.max_retries=0",
        "llm.timeout=10",
        "episode_length=6",
        "clock=lockstep",
        f"episodes={episodes}",
        *extra,
    ]
