"""`pillagerbench run`: play a match and record it.

    pillagerbench run scenario=mushroom_war red=passive blue=balanced episodes=3 episode_length=120

The run directory (printed first and last) holds manifest.json, episodes.jsonl (one line per
finished episode) and per episode its events, score timeline, game-master log and team artefacts.
An episode that fails (a bot or the server dies) is recorded as failed and the series goes on;
Ctrl-C ends the match cleanly, keeping every finished episode.
"""

from __future__ import annotations

import asyncio
import json
import platform
import subprocess
import time
from dataclasses import asdict
from pathlib import Path

from omegaconf import OmegaConf

from pillagerbench import __version__
from pillagerbench.arena import ArenaServer
from pillagerbench.config import load_config
from pillagerbench.display import MatchDisplay
from pillagerbench.match import Match
from pillagerbench.scenarios import make_scenario
from pillagerbench import preflight
from pillagerbench.preflight import team_llm_config, team_options
from pillagerbench.teams import make_team
from pillagerbench.validate import check_run_config


def git_revision() -> str | None:
    try:
        return subprocess.run(["git", "rev-parse", "HEAD"], capture_output=True, text=True, timeout=5,
                              cwd=Path(__file__).parent).stdout.strip() or None
    except (OSError, subprocess.SubprocessError):
        return None


def make_run_dir(cfg) -> Path:
    if cfg.run_dir:
        return Path(cfg.run_dir)
    stamp = time.strftime("%Y-%m-%d_%H-%M-%S")
    return Path("runs") / f"{stamp}_{cfg.scenario.name}_{cfg.red.name}_vs_{cfg.blue.name}"


def write_manifest(run_dir: Path, cfg, scenario) -> None:
    from pillagerbench.node import node_binary

    node = subprocess.run([str(node_binary()), "--version"], capture_output=True, text=True).stdout.strip()
    manifest = {
        "created": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        "config": OmegaConf.to_container(cfg, resolve=True),
        "scenario": {"key": scenario.key, "title": scenario.title, "version": scenario.version},
        "versions": {"pillagerbench": __version__, "python": platform.python_version(), "node": node,
                     "minecraft": "1.16.5"},
        "seed": cfg.seed,
        "git_revision": git_revision(),
    }
    (run_dir / "manifest.json").write_text(json.dumps(manifest, indent=1, default=str))


def make_llms(cfg, teams: dict, run_dir: Path) -> dict:
    from pillagerbench.llm import LLMClient

    return {side: LLMClient.from_config(team_llm_config(cfg, side), team=side, run_dir=run_dir)
            for side, team in teams.items() if team.uses_llm}


async def play(cfg, run_dir: Path) -> list:
    scenario = make_scenario(cfg.scenario.name, crop_growth_chance=float(cfg.scenario.crop_growth_chance))
    teams = {"red": make_team(cfg.red.name, scenario.key, **team_options(cfg.red)),
             "blue": make_team(cfg.blue.name, scenario.key, **team_options(cfg.blue))}
    write_manifest(run_dir, cfg, scenario)
    records = []
    title = f"{scenario.title}: red {cfg.red.name} vs blue {cfg.blue.name}"
    with MatchDisplay(title, cfg.display) as display:
        server = ArenaServer.from_config(cfg.server, log_path=run_dir / "server.log")
        await server.start()
        llms = make_llms(cfg, teams, run_dir)
        match = Match(server, scenario, teams, run_dir, episode_length=cfg.episode_length, seed=cfg.seed,
                      on_tick=display.tick, llms=llms)
        try:
            await match.setup()

            def done(rec) -> None:
                with open(run_dir / "episodes.jsonl", "a") as f:
                    f.write(json.dumps(asdict(rec)) + "\n")
                records.append(rec)
                display.episode_done(rec)

            await match.play_episodes(range(int(cfg.episodes)), done)
        finally:
            await match.close()
            await server.stop()
            for llm in llms.values():
                await llm.aclose()
    return records


def summarize_problems(records: list) -> tuple[list[str], bool]:
    """Lines about episodes in which a team had problems (its model or its server never answered,
    ...), and whether every episode of some team went that way."""
    lines, all_failed = [], False
    for side in ("red", "blue"):
        hit = [r for r in records if side in (r.problems or {})]
        if hit:
            lines.append(f"{side} {getattr(hit[0], side)} had problems in {len(hit)} of {len(records)} "
                         f"episode(s), e.g.: {hit[-1].problems[side][-1]}")
            all_failed = all_failed or len(hit) == len(records)
    return lines, all_failed


def main(argv: list[str]) -> int:
    cfg = load_config(argv)
    experiment = cfg.get("experiment") is not None or bool(cfg.get("resume"))
    check_run_config(cfg, teams=not experiment)
    if experiment:  # many series, parallel, resumable
        from pillagerbench.experiments.runner import main_experiment

        return main_experiment(cfg, argv)
    preflight.check(preflight.sides_of(cfg))
    run_dir = make_run_dir(cfg)
    run_dir.mkdir(parents=True, exist_ok=True)
    print(f"run directory: {run_dir}", flush=True)
    try:
        records = asyncio.run(play(cfg, run_dir))
    except KeyboardInterrupt:
        print("interrupted: finished episodes are kept in episodes.jsonl")
        print(f"run directory: {run_dir}")
        return 130
    failed = sum(r.status != "ok" for r in records)
    problems, all_without_model = summarize_problems(records)
    print(f"{len(records)} episode(s), {failed} failed")
    for line in problems:
        print(line)
    print(f"run directory: {run_dir}")
    return 1 if (failed and failed == len(records)) or all_without_model else 0
