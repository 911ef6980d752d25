"""Run directories written by hand (the files a real run writes), for metric and loader tests."""

from __future__ import annotations

import json
from pathlib import Path


def write_run(
    run: Path,
    scenario: str,
    red: str,
    blue: str,
    scores: list[tuple[float, float]],
    *,
    version: str = "1",
    length: int = 4,
    iterations: list[int] | None = None,
) -> Path:
    run.mkdir(parents=True)
    config = {
        "scenario": {"name": scenario},
        "red": {"name": red},
        "blue": {"name": blue},
        "episodes": len(scores),
        "episode_length": length,
        "seed": 0,
    }
    (run / "manifest.json").write_text(
        json.dumps({"config": config, "scenario": {"key": scenario, "version": version}})
    )
    with open(run / "episodes.jsonl", "w") as f:
        for i, (r, b) in enumerate(scores):
            ep = run / f"episode_{i:03d}"
            ep.mkdir()
            timeline = [{"t": t, "red": r * t / length, "blue": b * t / length} for t in range(length)]
            timeline.append({"t": length, "red": r, "blue": b})
            (ep / "timeline.json").write_text(json.dumps(timeline))
            rec = {
                "scenario": scenario,
                "red": red,
                "blue": blue,
                "episode": i,
                "red_score": r,
                "blue_score": b,
                "status": "ok",
                "iterations": {"red": iterations or [1, 1], "blue": [1, 1]},
            }
            (ep / "episode.json").write_text(json.dumps(rec))
            f.write(json.dumps(rec) + "\n")
    return run
