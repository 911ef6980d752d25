"""A league entrant's identity is its entrant (rundir/entrant.py): a round's league.json stamps the id of
the entrant each roster entry plays as, the same its episodes record; a league directory stamped before
(16 hex digits of the league.yaml entry) still plays on, and a changed entrant is refused either way.
Rounds are "played" by hand (no server), as in test_add_and_budget.py."""

from __future__ import annotations

import json

import yaml  # type: ignore[import-untyped]  # pyyaml ships no stubs

from pillagerbench.cli.commands import main as cli_main
from pillagerbench.config.compose import load_config
from pillagerbench.config.schema import RunConfig
from pillagerbench.experiments.runner import load_experiment
from pillagerbench.league import play
from pillagerbench.league.compose import entrant_of_entry, match_config
from pillagerbench.league.rounds import STAMP, round_dirs
from pillagerbench.league.spec import RosterEntry, load_league
from pillagerbench.teams.entrant import entrant_of
from tests.league.test_add_and_budget import play_by_hand


def test_an_entry_is_the_entrant_its_config_plays():
    cot = RosterEntry("c", "cot", llm="fake", llm_options={"model": "m2"})
    assert entrant_of_entry(cot).label == "cot@m2"
    config = match_config("mushroom_war", RosterEntry("x", "balanced"), cot)
    assert entrant_of_entry(cot) == entrant_of(config, "blue")  # on either side, against anyone
    assert entrant_of_entry(
        RosterEntry("other name", "cot", llm="fake", llm_options={"model": "m2"})
    ) == entrant_of_entry(cot)
    plain = entrant_of_entry(RosterEntry("r", "random", options={"pause_s": 2.0}))
    assert plain == entrant_of(RunConfig.of(load_config(["red=random", "red.pause_s=2"])), "red")
    assert plain.label == "random(pause_s=2)"


def _stamp(round_dir) -> dict:
    return json.loads((round_dir / STAMP).read_text())


def test_rounds_are_stamped_by_entrant_and_an_old_stamp_plays_on(tmp_path, capsys, monkeypatch):
    root = tmp_path / "L"
    assert cli_main(["league", str(root), "init", "episodes_per_match=1", "matches_per_round=1"]) == 0
    monkeypatch.setattr(play, "_play_round", play_by_hand)
    assert cli_main(["league", str(root), "play", "budget.episodes=2", "display=plain"]) == 0
    (first,) = round_dirs(root)
    stamped = _stamp(first)["entrants"]
    for spec in load_experiment(first)[1]:  # the id each series' episodes record for its sides
        for side, name in (("red", spec.red), ("blue", spec.blue)):
            assert stamped[name] == entrant_of(spec.config, side).id

    league = load_league(root)  # the round as a league before the entrant type stamped it
    old = {name: league.entrant(name).old_fingerprint() for name in stamped}
    assert all(len(v) == 16 for v in old.values())
    (first / STAMP).write_text(json.dumps({**_stamp(first), "entrants": old}))
    capsys.readouterr()
    assert cli_main(["league", str(root), "play", "budget.episodes=4", "display=plain"]) == 0, capsys.readouterr().err
    assert len(round_dirs(root)) == 2 and all(len(v) == 12 for v in _stamp(round_dirs(root)[1])["entrants"].values())
    assert cli_main(["league", str(root), "board"]) == 0

    changed = sorted(old)[0]  # the league.yaml entry of an entrant the old round played changes
    raw = yaml.safe_load((root / "league.yaml").read_text())
    for e in raw["entrants"]:
        if e["name"] == changed:
            e["team"] = "passive" if e["team"] != "passive" else "balanced"
    (root / "league.yaml").write_text(yaml.safe_dump(raw, sort_keys=False))
    (round_dirs(root)[1] / STAMP).write_text(json.dumps({**_stamp(round_dirs(root)[1]), "entrants": {}}))
    capsys.readouterr()
    assert cli_main(["league", str(root), "board"]) == 2  # refused by the old stamp alone
    assert f"round_000: entrant {changed!r} was another team" in capsys.readouterr().err
