"""docs/your-team.md, executed: its code blocks are the files of examples/, and its command blocks
run in order in a scratch folder on the real server (the LLM team against the fake provider); each
kind of team then has played one scored episode, and the report covers all four."""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "your-team.md"
BLOCK = re.compile(r"<!-- (file: (?P<file>\S+)|run) -->\n```(?P<lang>\w+)\n(?P<body>.*?)```\n", re.S)


def blocks():
    return [(m["file"], m["lang"], m["body"]) for m in BLOCK.finditer(DOC.read_text())]


def test_every_code_block_is_an_example_file():
    files = [(f, body) for f, _, body in blocks() if f]
    assert {f for f, _ in files} == {f"examples/{p.name}" for p in (ROOT / "examples").iterdir() if p.is_file()}
    for f, body in files:
        assert body == (ROOT / f).read_text(), f"docs/your-team.md's block of {f} differs from the file"


def _run(script: str, cwd: Path, n: int) -> subprocess.CompletedProcess:
    env = dict(os.environ, PATH=f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}")
    log = cwd / f"block_{n}.log"
    with open(log, "w") as out:  # a file, not a pipe: a background server keeps a pipe open
        proc = subprocess.Popen(
            ["bash", "-e", "-c", script], cwd=cwd, env=env, stdout=out, stderr=subprocess.STDOUT, start_new_session=True
        )
        try:
            proc.wait(timeout=240)
        finally:
            try:
                os.killpg(proc.pid, signal.SIGKILL)  # background servers the block started
            except ProcessLookupError:
                pass
    return subprocess.CompletedProcess(script, proc.returncode, log.read_text(), "")


def _episode(run: Path) -> dict:
    lines = (run / "episodes.jsonl").read_text().splitlines()
    assert len(lines) == 1
    return json.loads(lines[0])


@pytest.fixture(scope="module")
def tutorial(tmp_path_factory):
    work = tmp_path_factory.mktemp("your-team")
    shutil.copytree(ROOT / "examples", work / "examples")
    results = [_run(body, work, n) for n, (f, lang, body) in enumerate(blocks()) if not f]
    return work, results


@pytest.mark.timeout(900)  # the fixture plays four episodes
def test_every_command_block_runs(tutorial):
    _, results = tutorial
    assert len(results) == 5
    for r in results:
        assert r.returncode == 0, f"{r.args}\n---\n{r.stdout[-3000:]}"


def test_each_kind_of_team_played_and_scored_or_ran_its_programs(tutorial):
    work, _ = tutorial
    runs = work / "runs"
    scripted = _episode(runs / "scripted")
    assert scripted["status"] == "ok" and sum(scripted["iterations"]["red"]) > 0, scripted
    # it harvested (a mushroom block drops nothing 7 times in 9, so a 20 s score may well be 0)
    events = [json.loads(line) for line in (runs / "scripted" / "episode_000" / "world_events.jsonl").open()]
    dug = [e for e in events if e["event"] == "block_dug" and e["block"] == "red_mushroom_block"]
    assert {e["player"] for e in dug} == {"Ryn", "Raze"}, events[:5]
    llm = _episode(runs / "llm")
    assert llm["status"] == "ok" and sum(llm["iterations"]["red"]) > 0 and not llm["problems"], llm
    calls = [json.loads(line) for line in (runs / "llm" / "llm_calls.jsonl").read_text().splitlines()]
    assert len(calls) == 2 and all(c["team"] == "red" and c["error"] is None for c in calls)
    for name in ("remote_py", "remote_js"):
        rec = _episode(runs / name)
        assert rec["status"] == "ok" and sum(rec["iterations"]["red"]) >= 2 and not rec["problems"], rec
        remote = json.loads((runs / name / "episode_000" / "red" / "remote.json").read_text())
        assert [c["path"] for c in remote["calls"]][:2] == ["/pregame", "/events"]
        assert not any("error" in c for c in remote["calls"])
    js = json.loads((runs / "remote_js" / "episode_000" / "red" / "remote.json").read_text())
    assert "new orders" in json.dumps(js["programs"])
    chat = (runs / "remote_js" / "episode_000" / "chat.txt").read_text()
    assert "new orders" in chat


def test_the_report_covers_every_team(tutorial):
    work, _ = tutorial
    summary = (work / "runs" / "report" / "summary.csv").read_text()
    for team in ("scripted_team:Harvesters", "llm_team:OneShot", "remote"):
        assert team in summary
