"""`pillagerbench league LEAGUE_DIR COMMAND ...` (docs/league.md):

init  [scenarios=[a,b]] [episodes_per_match=N] [KEY=VALUE]   a new league with the built-in opponents
add   NAME team=TEAM [llm=PRESET] [OPTION=VALUE] [llm.KEY=VALUE]   a new entrant (creates the league if needed)
play  [league keys, e.g. budget.episodes=4] [run overrides, e.g. episode_length=20] [parallel=N]
board [mix_suites=true] [no_verify=true] [split=test]       leaderboard.md, .csv, .html

Rounds of different suite versions are refused unless mix_suites=true, handed-over bundles that fail
their checks (pillagerbench verify) unless no_verify=true (then the board says so).
split=test (league.yaml or play/board) plays and rates on fresh test layouts (league/splits.py).
"""

from __future__ import annotations

from pathlib import Path

from pillagerbench.config.compose import ConfigError
from pillagerbench.config.schema import RunnerConfig, check, problems
from pillagerbench.experiments.spec import builtin_teams
from pillagerbench.league.board import write_board
from pillagerbench.league.compose import check_entrant
from pillagerbench.league.play import RUNNER, play
from pillagerbench.league.rounds import check_stamps
from pillagerbench.league.spec import (
    League,
    RosterEntry,
    league_path,
    load_league,
    parse_value,
    save_league,
    with_overrides,
)

COMMANDS = ("init", "add", "play", "board")


def _pairs(args: list[str]) -> dict[str, object]:
    out = {}
    for a in args:
        key, sep, value = a.partition("=")
        if not sep or not key:
            raise ConfigError(f"{a!r}: expected KEY=VALUE")
        out[key] = parse_value(value)
    return out


def _league_keys(pairs: dict) -> tuple[dict, dict]:
    """(league.yaml keys, everything else)."""
    fields = set(League.__dataclass_fields__) - {"entrants"}
    ours = {k: v for k, v in pairs.items() if k.partition(".")[0] in fields}
    return ours, {k: v for k, v in pairs.items() if k not in ours}


def new_league(league_dir: Path, args: list[str]) -> League:
    """A new league with the built-in opponents, checked but not saved yet."""
    if league_path(league_dir).exists():
        raise ConfigError(f"{league_path(league_dir)} exists already; this directory holds a league")
    ours, other = _league_keys(_pairs(args))
    if other:
        raise ConfigError(
            f"init: {next(iter(other))!r} is not a league key; valid: {', '.join(League.__dataclass_fields__)}"
        )
    league = with_overrides(League(), ours)
    names = dict.fromkeys(n for sc in league.scenarios for n in builtin_teams(sc))
    league.entrants = [RosterEntry(name=n, team=n) for n in names]
    for e in league.entrants:
        check_entrant(e, league.scenarios)
    return league


def _created(league_dir: Path, league: League) -> str:
    return f"{league_path(league_dir)}: {len(league.entrants)} entrants ({', '.join(e.name for e in league.entrants)})"


def init(league_dir: Path, args: list[str]) -> League:
    league = new_league(league_dir, args)
    save_league(league_dir, league)
    print(_created(league_dir, league))
    return league


def add(league_dir: Path, args: list[str]) -> None:
    if not args or "=" in args[0]:
        raise ConfigError("add NAME team=TEAM [llm=PRESET] [OPTION=VALUE ...] [llm.KEY=VALUE ...]")
    name, pairs = args[0], _pairs(args[1:])
    created = not league_path(league_dir).exists()  # written only once the entrant passes its checks
    league = new_league(league_dir, []) if created else load_league(league_dir)
    if league.entrant(name):
        raise ConfigError(f"an entrant named {name!r} exists already in {league_path(league_dir)}; choose another name")
    team, llm = pairs.pop("team", None), pairs.pop("llm", None)
    if not team:
        raise ConfigError(f"add {name}: team=TEAM is required (see `pillagerbench teams`)")
    entrant = RosterEntry(
        name=name,
        team=str(team),
        options={k: v for k, v in pairs.items() if not k.startswith("llm.")},
        llm=None if llm is None else str(llm),
        llm_options={k[4:]: v for k, v in pairs.items() if k.startswith("llm.")},
    )
    check_entrant(entrant, league.scenarios)
    if created:
        print(_created(league_dir, league))
    league.entrants.append(entrant)
    save_league(league_dir, league)
    print(f"{league_path(league_dir)}: added {name} (team {entrant.team}); {len(league.entrants)} entrants")


def main(argv: list[str]) -> int:
    if len(argv) < 2 or argv[1] not in COMMANDS:
        raise ConfigError(f"usage: pillagerbench league LEAGUE_DIR {{{'|'.join(COMMANDS)}}} [KEY=VALUE ...]")
    league_dir, command, rest = Path(argv[0]), argv[1], argv[2:]
    if command == "init":
        init(league_dir, rest)
        return 0
    if command == "add":
        add(league_dir, rest)
        return 0
    league = load_league(league_dir)
    if command == "board":
        ours, other = _league_keys(_pairs(rest))
        if other:
            raise ConfigError(f"board: {next(iter(other))!r} is not a league key (e.g. mix_suites=true)")
        league = with_overrides(league, ours)
        check_stamps(league_dir, league, None)
        for path in write_board(league_dir, league):
            print(path)
        return 0
    ours, other = _league_keys(_pairs(rest))
    given = {k: v for k, v in other.items() if k in RUNNER}
    check(problems(RunnerConfig, given))
    defaults = RunnerConfig.model_validate({})  # conf/config.yaml's; every key of RUNNER is written to a round
    runner = RunnerConfig.model_validate({k: getattr(defaults, k) for k in RUNNER} | given)
    game = tuple(a for a in rest if a.partition("=")[0] in other and a.partition("=")[0] not in RUNNER)
    for a in game:
        if a.partition("=")[0].split(".")[0].lstrip("+~") in ("red", "blue", "scenario", "experiment", "resume"):
            raise ConfigError(
                f"{a!r}: a league chooses scenarios and teams itself (scenarios=[...], entrants in league.yaml)"
            )
    league = with_overrides(league, ours)
    code = play(league_dir, league, game, runner)
    write_board(league_dir, league)
    print(f"board: {league_dir / 'leaderboard.md'}")
    return code
