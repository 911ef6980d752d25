"""A person's results end to end (issue 54): one real match (a real server, real bots, the real clock) with a
person's seat taken and made ready through the page server's HTTP endpoints, as page.html does, beside a
built-in team's run against the same opponent on the same seed; then `pillagerbench report` over both shows
the person's entrant (`do_nothing+human:Ryn`) in its own rows, paired against the built-in team in the
differences table; `pillagerbench compare` and a league, which play their matches themselves, refuse
people in one line; a league does not count a person's run handed over as a bundle. The page's feed tells
the final score at each whistle and what comes next."""

from __future__ import annotations

import csv
import subprocess
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import httpx
import pytest

from pillagerbench.rundir import RunDir
from pillagerbench.rundir.faults import spoiled
from tests.support.cli import refused_in_process, run_cli, start_cli
from tests.support.people import page_url

EPISODE_S = 6
EPISODES = 2
PERSON = "do_nothing+human:Ryn"  # rundir/entrant.py: the team's label, then each person's human:NAME
GAME = [f"episode_length={EPISODE_S}", f"episodes={EPISODES}", "blue=passive", "display=plain", "retries=0"]


@dataclass
class Played:
    person: Path  # the person's run directory
    builtin: Path  # do_nothing's, against the same opponent on the same seed
    feed: list[str]  # the page's events feed, as the person's page last read it
    states: list[dict]  # every distinct (phase, final, next) the page read


def _seat(url: str, proc: subprocess.Popen) -> tuple[list[str], list[dict]]:
    """Take the seat of the player Ryn under the name Ryn, press Ready, and read the page's state until the run ends."""
    feed: list[str] = []
    states: list[dict] = []
    with httpx.Client(base_url=url, timeout=10) as page:
        token = page.post("join", json={"name": "Ryn", "player": "Ryn"}).json()["result"]["token"]
        assert page.post("ready", json={"token": token}).json()["ok"]
        while proc.poll() is None:
            try:
                state = page.get("state", params={"token": token}).json()
            except httpx.TransportError:  # the run is over: the match stopped the page's server
                break
            feed = state["feed"]
            seen = {"phase": state["phase"], "final": state["board"].get("final"), "next": state["next"]}
            if not states or states[-1] != seen:
                states.append(seen)
    return feed, states


@pytest.fixture(scope="module")
def played(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Played]:
    root = tmp_path_factory.mktemp("results")
    person, builtin = root / "person", root / "builtin"
    proc = start_cli("run", "red=do_nothing", "red.humans=[Ryn]", *GAME, f"run_dir={person}", cwd=root)
    other = start_cli("run", "red=do_nothing", *GAME, f"run_dir={builtin}", cwd=root)  # meanwhile
    try:
        feed, states = _seat(page_url(proc), proc)
        assert proc.wait(timeout=90) == 0 and other.wait(timeout=90) == 0
    finally:
        for p in (proc, other):
            p.kill()
    yield Played(person, builtin, feed, states)


def _rows(path: Path) -> list[dict[str, str]]:
    with path.open() as f:
        return list(csv.DictReader(f))


def _used(run: Path) -> set[int]:
    """The seeds of a run's episodes the report uses (finished, not spoiled on our side: rundir/faults.py)."""
    return {r.seed for r in RunDir(run).finished().values() if r.status == "ok" and not spoiled(r)}


def test_the_report_gives_the_person_rows_of_their_own(played: Played, tmp_path: Path):
    done = run_cli(tmp_path, "report", str(played.person), str(played.builtin), "--out", "rep", "--no-replays")
    assert done.returncode == 0, done.stderr
    out = tmp_path / "rep"
    summary = {r["red"]: r for r in _rows(out / "summary.csv")}
    assert set(summary) == {PERSON, "do_nothing"}, summary
    assert summary[PERSON]["planned"] == str(EPISODES)
    provenance = {Path(r["run"]).name: r["entrants"] for r in _rows(out / "provenance.csv")}
    if _used(played.person):  # the entrants of the episodes used: none when every one was lagged (load)
        assert PERSON in provenance["person"], provenance
    assert "human" not in provenance["builtin"], provenance
    both = _used(played.person) and _used(played.builtin)
    if both:  # (an episode played under lag is in no score: then the table has nothing to pair)
        diffs = [r for r in _rows(out / "differences.csv") if {r["a"], r["b"]} == {PERSON, "do_nothing"}]
        assert len(diffs) == 1 and diffs[0]["opponent"] == "passive", diffs
        shared = len(_used(played.person) & _used(played.builtin))
        assert diffs[0]["design"] == (f"paired ({shared} pairs)" if shared >= 2 else "unpaired"), diffs  # paired.py


def test_the_persons_run_is_stopped_at_every_whistle(played: Played):
    """The person's run, started again after the whistle's stop, was left going: the next whistle's stop waited
    for it in vain and restarted the bot, spoiling every second episode (people/relay.py `end`)."""
    records = RunDir(played.person).finished().values()
    assert len(records) == EPISODES and not [r.stall_reason for r in records if "Ryn" in (r.stall_reason or "")]


def test_the_page_told_each_whistle_and_what_came_next(played: Played):
    feed = played.feed
    whistles = [i for i, line in enumerate(feed) if line.startswith("the whistle: ") and line.endswith("(final)")]
    assert whistles, feed  # (the last whistle's line may come after the page's last read: the run ends with it)
    nexts = [line for line in feed[whistles[0] :] if line.startswith("next: episode ")]
    assert nexts and nexts[0] == "next: episode 2", feed  # told after the first whistle, before the game went on
    over = [s for s in played.states if s["phase"] == "over" and s["final"] is not None]
    assert over and set(over[0]["final"]) == {"red", "blue"}, played.states


def test_compare_and_a_league_refuse_people_in_one_line(played: Played, tmp_path: Path, monkeypatch, capsys):
    said = refused_in_process(monkeypatch, capsys, tmp_path, "compare", "human", "passive", "opponent=do_nothing")
    assert "people would play red" in said[0] and "pillagerbench report" in said[0], said
    league = tmp_path / "L"
    for given in (["team=human"], ["team=do_nothing", "humans=[Ryn]"]):
        said = refused_in_process(monkeypatch, capsys, tmp_path, "league", str(league), "add", "ryn", *given)
        assert said[0].startswith("pillagerbench league: entrant 'ryn': people would play red"), said
        assert not league.exists()  # a refused add writes nothing


def test_a_league_does_not_count_a_persons_run_handed_over(played: Played, tmp_path: Path, monkeypatch, capsys):
    league = tmp_path / "L"
    assert run_cli(tmp_path, "league", str(league), "init").returncode == 0
    bundle = league / "matches" / "ryn.tar.gz"
    exported = run_cli(tmp_path, "export", str(played.person), "--out", str(bundle))
    assert exported.returncode == 0, exported.stderr
    said = refused_in_process(monkeypatch, capsys, tmp_path, "league", str(league), "board")
    assert "not a round of a league" in said[0], said
