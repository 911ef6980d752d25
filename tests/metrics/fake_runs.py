"""Run directories written by hand (the files a real run writes), for metric and loader tests."""

from __future__ import annotations

import json
from pathlib import Path

from pillagerbench.scenarios.layout import split_of
from tests.support.configs import run_config


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
    first_points: list[int] | None = None,
    upstream: list[tuple[float, float]] | None = None,
    lagged: dict[int, str] | None = None,
    suite: str | None = None,
    failed: dict[int, str] | None = None,
    problems: dict[int, dict[str, list[str]]] | None = None,
    layouts: list[str | int] | None = None,
    protocol: str | None = None,
    seeds: list[int] | None = None,
    conditions: dict | None = None,
) -> Path:
    """One plain run. Per episode i: `first_points[i]` the second red's score leaves 0 (default 1),
    `upstream[i]` upstream's scoring too, `lagged[i]` played under lag (why), `failed[i]` failed (error),
    `problems[i]` by side, `layouts[i]` ("paper", a seed or a file), `seeds[i]`. Every record: `suite`,
    `protocol`, `conditions` (more rules played under). None of these: a record from before them."""
    run.mkdir(parents=True)
    base = run_config().stored()  # a real run's config: every key composed
    config = {
        **base,
        "scenario": {**base["scenario"], "name": scenario},
        "red": {"name": red},
        "blue": {"name": blue},
        "episodes": len(scores),
        "episode_length": length,
        "seed": 0,
    }
    manifest = {"config": config, "scenario": {"key": scenario, "version": version}}
    if suite:  # the manifest names the suite its episodes were played under, as a real run's does
        manifest["suite"] = {"label": suite}
    (run / "manifest.json").write_text(json.dumps(manifest))
    with open(run / "episodes.jsonl", "w") as f:
        for i, (r, b) in enumerate(scores):
            ep = run / f"episode_{i:03d}"
            ep.mkdir()
            start = first_points[i] if first_points else 1
            timeline = [
                {"t": t, "red": r * t / length if t >= start else 0.0, "blue": b * t / length} for t in range(length)
            ]
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
            given = {"suite": suite, "protocol": protocol, "seed": seeds[i] if seeds else None}
            rec.update({k: v for k, v in given.items() if v is not None})
            if conditions:  # rules recorded as the match records them (e.g. clock.mode)
                rec["conditions"] = {**({"protocol": protocol} if protocol else {}), **conditions}
            if layouts:
                rec.update(layout=layouts[i], split=split_of(layouts[i]))
            if failed and i in failed:
                rec.update(status="failed", error=failed[i], red_score=None, blue_score=None)
            if problems and i in problems:
                rec["problems"] = problems[i]
            if lagged and i in lagged:
                rec.update(lagged=True, lag_reason=lagged[i], server_tps=12.5)
            if upstream:
                rec["scoring"] = "upstream"
                rec["red_score"], rec["blue_score"] = upstream[i]
                rec["scores"] = {"clean": {"red": r, "blue": b}, "upstream": dict(zip(("red", "blue"), upstream[i]))}
            (ep / "episode.json").write_text(json.dumps(rec))
            f.write(json.dumps(rec) + "\n")
    return run
