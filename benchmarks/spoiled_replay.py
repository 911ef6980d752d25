"""What playing spoiled episodes again costs (issue 37, "Our faults are never a team's result").

One series of cot (on the fake LLM provider, pillagerbench.llm.fake_server, answering a short
program) against do_nothing on the real server, `--episodes` planned of `--episode-length` s, with the
provider answering 503 for its first `--outage` episodes (0: no outage). Prints one JSON line: wall
seconds of the series, episodes played, used, spoiled (by the outage, by lag) and given up. An
episode spoiled by lag (this machine's load) is played again too: its count is printed apart.

    python benchmarks/spoiled_replay.py --outage 0      # the series without outage
    python benchmarks/spoiled_replay.py --outage 1      # the provider down for one episode
    python benchmarks/spoiled_replay.py --both          # both in turn, and the cost of the outage
    python benchmarks/spoiled_replay.py --both --no-lag # the same, lag not judged (a loaded machine)
"""

from __future__ import annotations

import argparse
import asyncio
import json
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))
from pillagerbench.config.compose import load_config, to_dict
from pillagerbench.experiments.series import run_series
from pillagerbench.llm.fake_server import FakeLLMServer, Rule
from pillagerbench.rundir import RunDir, SeriesSpec, faults, progress

WAIT = "async function main(bot) {\n  await bot.waitForTicks(20)\n}"
ANSWER = "Plan: wait.\n" + "\n".join(f"Code for bot {i}:\n```javascript\n{WAIT}\n```" for i in range(2))


def kinds(records: dict[int, dict]) -> dict[str, int]:
    """Episodes spoiled on our side, per kind of fault of ours (an episode may have two: outage and lag)."""
    out: dict[str, int] = {}
    for rec in records.values():
        for kind in dict.fromkeys(f["kind"] for f in faults(rec) if f["whose"] == "harness"):
            out[kind] = out.get(kind, 0) + 1
    return out


def no_lag_verdict() -> None:
    """Lag thresholds out of reach (pillagerbench.host.machine): on a loaded machine, only the outage spoils."""
    from pillagerbench.host import machine

    machine.SERVER_TPS_MIN = machine.BOT_TICK_RATE_MIN = 0.0
    machine.BOT_LATE_MEAN_MS_MAX, machine.BOT_LATE_PCT_MAX = 1e9, 101.0


async def series(outage: int, episodes: int, length: float, retries: int, where: Path) -> dict:
    with FakeLLMServer() as fake:
        fake.add(*([Rule(status=503, message="the provider is down")] if outage else []), Rule(reply=ANSWER))
        overrides = ["scenario=mushroom_war", "red=cot", "blue=do_nothing", "llm=fake", f"llm.base_url={fake.url}"]
        overrides += ["llm.max_retries=0", f"episode_length={length}", f"episodes={episodes}", f"retries={retries}"]
        cfg = to_dict(load_config(overrides))
        spec = SeriesSpec("run", 0, "run", "mushroom_war", "cot", "do_nothing", "cot", "do_nothing", episodes, 0, cfg)
        played: list[int] = []

        def after(rec) -> None:
            played.append(rec.episode)
            if len(played) == outage:  # the provider is back
                fake.reset()
                fake.add(Rule(reply=ANSWER))

        t0 = time.monotonic()
        await run_series(spec, where, on_episode=after, say=lambda _: None)
        wall = time.monotonic() - t0
    records = RunDir(where).finished()
    done = progress(records, episodes, retries)
    return {
        "outage": outage,
        "planned": episodes,
        "played": len(records),
        "used": done.used,
        "spoiled": kinds(records),
        "given_up": done.given_up,
        "wall_s": round(wall, 1),
    }


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--outage", type=int, default=1, help="episodes at the start with the provider down")
    p.add_argument("--episodes", type=int, default=3)
    p.add_argument("--episode-length", type=float, default=10)
    p.add_argument("--retries", type=int, default=2)
    p.add_argument("--both", action="store_true", help="without outage, then with --outage; and the cost")
    p.add_argument("--no-lag", action="store_true", help="judge no episode lagged (isolates the outage's cost)")
    a = p.parse_args()
    if a.no_lag:
        no_lag_verdict()
    rows = []
    for outage in (0, a.outage) if a.both else (a.outage,):
        with tempfile.TemporaryDirectory() as tmp:
            rows.append(asyncio.run(series(outage, a.episodes, a.episode_length, a.retries, Path(tmp) / "run")))
            print(json.dumps(rows[-1]), flush=True)
    if a.both:
        calm, hit = rows
        cost = {
            "extra_episodes": hit["played"] - calm["played"],
            "extra_wall_s": round(hit["wall_s"] - calm["wall_s"], 1),
        }
        print(json.dumps(cost))


if __name__ == "__main__":
    main()
