"""League commands without a server: `add` refusing an entrant in one line and writing nothing, and
each budget kind (episodes, hours, LLM tokens, LLM cost) stopping `play`, counted from episode
records and ledgers written by hand in place of played rounds."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml  # type: ignore[import-untyped]  # pyyaml ships no stubs

from pillagerbench.cli.commands import main as cli_main
from pillagerbench.experiments.runner import load_experiment
from pillagerbench.league import play
from pillagerbench.league.rounds import round_dirs
from pillagerbench.rundir import EPISODES, LEDGER


@pytest.mark.parametrize(
    "args, expected",
    [
        (["x", "team=nonexistent"], "entrant 'x': unknown team 'nonexistent'; known: "),
        (
            ["x", "team=berries"],
            "entrant 'x': team berries plays none of the league's scenarios (mushroom_war); it plays dash_and_dine",
        ),
        (["x", "team=balanced", "aggression=9"], "entrant 'x': team.aggression: unknown key (options of balanced"),
        (["x", "team=random", "pause_every=often"], "entrant 'x': team.pause_every='often': input should be"),
        (["x", "team=cot", "llm=nope"], "entrant 'x': unknown llm preset 'nope'; known: "),
        (["x", "team=cot", "llm.budget.max_bananas=1"], "entrant 'x': team.llm.budget.max_bananas: unknown key"),
        (["x", "llm=fake"], "add x: team=TEAM is required"),
        (["balanced", "team=passive"], "an entrant named 'balanced' exists already"),
    ],
    ids=[
        "unknown_team",
        "team_not_for_the_scenario",
        "unknown_option",
        "bad_option_value",
        "unknown_llm_preset",
        "unknown_llm_option",
        "no_team",
        "name_taken",
    ],
)
def test_add_refuses_in_one_line_and_writes_nothing(tmp_path, capsys, args, expected):
    root = tmp_path / "L"

    def refused() -> None:
        assert cli_main(["league", str(root), "add", *args]) == 2
        err = capsys.readouterr().err.splitlines()
        assert len(err) == 1 and err[0].startswith("pillagerbench league: ") and expected in err[0], err

    refused()  # no league yet: `add` would create one, but not for an entrant it refuses
    assert not root.exists()
    assert cli_main(["league", str(root), "init"]) == 0
    before = (root / "league.yaml").read_bytes()
    refused()
    assert (root / "league.yaml").read_bytes() == before


SPENT_PER_EPISODE = {"episodes": 1, "hours": 0.5, "llm_tokens": 1000, "llm_cost_usd": 0.25}


def play_by_hand(run_dir: Path, runner: dict) -> bool:
    """Stands in for playing a round: each series gets one (failed) episode of half an hour and a
    ledger of one call of 600 + 400 tokens costing $0.25. It failed on the team's budget, a team's own
    failure: a failure of ours would be played again (rundir/schedule.py)."""
    if len(round_dirs(run_dir.parents[1])) > 4:
        return False  # the budget should have stopped the league by now: stop as a failed round does
    for series in load_experiment(run_dir)[2].values():
        series.mkdir(parents=True)
        record = {"episode": 0, "status": "failed", "error": "BudgetExceeded: by hand", "duration_s": 1800}
        (series / EPISODES).write_text(json.dumps(record) + "\n")
        call = {"team": "red", "input_tokens": 600, "output_tokens": 400, "cost_usd": 0.25}
        (series / LEDGER).write_text(json.dumps(call) + "\n")
    return True


@pytest.mark.parametrize("kind", SPENT_PER_EPISODE)
def test_each_budget_kind_stops_play(tmp_path, capsys, monkeypatch, kind):
    root = tmp_path / "L"
    assert cli_main(["league", str(root), "init", "episodes_per_match=1", "matches_per_round=1"]) == 0
    monkeypatch.setattr(play, "_play_round", play_by_hand)
    limit = 4 * SPENT_PER_EPISODE[kind]  # two rounds of one match and its side-swapped twin, one episode each
    command = ["league", str(root), "play", f"budget.{kind}={limit}", "display=plain"]
    spent = f"({kind} {limit:g}/{limit:g})"

    assert cli_main(command) == 0
    assert f"league stopped: budget spent {spent}" in capsys.readouterr().out
    assert len(round_dirs(root)) == 2

    assert cli_main(command) == 2  # played again: refused in one line, nothing new
    assert capsys.readouterr().err.splitlines() == [
        f"pillagerbench league: budget already spent {spent}; raise it (e.g. budget.episodes=N) to play more"
    ]
    assert len(round_dirs(root)) == 2


def test_add_creates_the_league_it_needs(tmp_path, capsys):
    root = tmp_path / "L"
    assert cli_main(["league", str(root), "add", "random_7", "team=random", "pause_every=7"]) == 0
    league = yaml.safe_load((root / "league.yaml").read_text())
    names = ["do_nothing", "aggressive", "balanced", "passive", "slimy", "random_7"]
    assert [e["name"] for e in league["entrants"]] == names
    assert league["entrants"][-1] == {
        "name": "random_7",
        "team": "random",
        "options": {"pause_every": 7},
        "llm": None,
        "llm_options": {},
    }
