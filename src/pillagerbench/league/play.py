"""`pillagerbench league LEAGUE_DIR play [overrides]`: rounds of scheduled matches until every
adjacent pair of every scenario's board is separated or the budget is spent.

Each round: finish an unfinished round first (resume, as `pillagerbench run resume=`), rebuild the
ratings from the episodes (each finished round read once: results.Played), check the budget, schedule (schedule.py), write the round directory
and play it through the experiment runner."""

from __future__ import annotations

import asyncio
from pathlib import Path

from pillagerbench.config.compose import ConfigError
from pillagerbench.config.schema import RunnerConfig
from pillagerbench.experiments.runner import check_series, execute, load_experiment, series_progress
from pillagerbench.league import results
from pillagerbench.league.compose import check_entrant
from pillagerbench.league.rounds import check_stamps, handed_over, round_dirs, write_round
from pillagerbench.league.schedule import next_round
from pillagerbench.league.spec import League
from pillagerbench.league.splits import check_game
from pillagerbench.league.standings import boards
from pillagerbench.metrics.verified import check_bundles

# how to play, not what: free to change between a league's rounds (the other keys of RunnerConfig are not a league's)
RUNNER = ("parallel", "launcher", "ray_address", "display")


def _unfinished(run_dir: Path) -> bool:
    _, specs, dirs = load_experiment(run_dir)
    return any(not series_progress(s, dirs[s.id]).complete for s in specs)


def _play_round(run_dir: Path, runner: RunnerConfig) -> bool:
    """Play (or finish) one round; False when a series failed."""
    title, specs, dirs = load_experiment(run_dir)
    check_series(specs)
    print(f"{run_dir.name}: " + ", ".join(f"{s.red} vs {s.blue} ({s.scenario})" for s in specs), flush=True)
    got = asyncio.run(execute(run_dir, title, specs, dirs, runner))
    return all(r["status"] == "done" for r in got.values())


def play(league_dir: Path, league: League, game: tuple[str, ...], runner: RunnerConfig) -> int:
    check_game(game)
    for e in league.entrants:
        check_entrant(e, league.scenarios, game)
    check_stamps(league_dir, league, game)
    if not league.no_verify:  # before anything is played: a handed-over bundle that fails its checks is refused
        check_bundles(handed_over(league_dir))
    start = results.spent(league_dir)
    if (over := start.over(league.budget)) and not (round_dirs(league_dir) and _unfinished(round_dirs(league_dir)[-1])):
        raise ConfigError(f"budget already spent ({over}); raise it (e.g. budget.episodes=N) to play more")
    played = results.Played(league_dir, league.mix_suites, not league.no_verify)
    while True:
        rounds = round_dirs(league_dir)
        if rounds and _unfinished(rounds[-1]):
            print(f"finishing {rounds[-1].name}", flush=True)
            if not _play_round(rounds[-1], runner):
                print(f"a series of {rounds[-1].name} failed; see its series_error.txt, then play again to finish it")
                return 1
            continue
        spent = played.spent()  # every round finished: each read once (results.Played)
        if over := spent.over(league.budget):
            print(f"league stopped: budget spent ({over})")
            return 0
        outs = played.outcomes(league.split)
        pairings = next_round(boards(league, outs), outs, league.confidence, league.matches_per_round)
        if not pairings:
            print(f"league settled: every adjacent pair is separated at confidence {league.confidence:g}")
            return 0
        episodes = league.episodes_per_match
        if league.budget.get("episodes") is not None:
            left = int(league.budget["episodes"] or 0) - spent.episodes
            pairings = pairings[: max(1, left // (2 * episodes))]  # a match is played with its side-swapped twin
            episodes = min(episodes, max(1, left // 2))
        run_dir, _ = write_round(league_dir, league, pairings, episodes, game, runner)
        if not _play_round(run_dir, runner):
            print(f"a series of {run_dir.name} failed; see its series_error.txt, then play again to finish it")
            return 1
