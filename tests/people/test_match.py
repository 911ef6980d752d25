"""A person plays a real match through the page's endpoints (people/page.py) on a real server with real
bots: a key and the mouse move and dig, a primitive button runs, a second page for the taken player is
refused, a page comes back into its player with its token; the server's record shows each."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import httpx


def _url(proc: subprocess.Popen) -> str:
    assert proc.stdout is not None
    for line in proc.stdout:
        if line.startswith("people: open "):
            return line.split()[2]
    raise AssertionError("no page address printed")


def test_a_person_walks_digs_and_presses_a_button(tmp_path: Path):
    run_dir = tmp_path / "run"
    cmd = [
        sys.executable,
        "-m",
        "pillagerbench.cli",
        "run",
        "red=do_nothing",
        "red.humans=[Ryn]",
        "blue=do_nothing",
        "episode_length=8",
        f"run_dir={run_dir}",
        "display=plain",
        "humans.ready_timeout_s=120",
    ]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=os.environ.copy())
    try:
        url = _url(proc)
        with httpx.Client(base_url=url, timeout=10) as page:
            token = page.post("join", json={"name": "alice", "player": "Ryn"}).json()["result"]["token"]
            second = page.post("join", json={"name": "mallory", "player": "Ryn"})
            assert second.status_code == 409 and "second page" in second.json()["error"]
            assert page.post("ready", json={"token": token}).json()["ok"]
            while page.get("state", params={"token": token}).json()["phase"] != "playing":
                time.sleep(0.1)
            start = page.get("state", params={"token": token}).json()
            assert start["seat"]["player"] == "Ryn"  # the same page, back with its token
            forward = {"what": "controls", "controls": {"forward": True}}
            assert page.post("act", json={"token": token, "input": forward}).json()["ok"]
            time.sleep(1.0)
            page.post("act", json={"token": token, "input": {"what": "controls", "controls": {}}})
            assert page.post("act", json={"token": token, "input": {"what": "look", "yaw": 0, "pitch": -1.5}}).json()[
                "ok"
            ]
            assert (
                page.post("act", json={"token": token, "input": {"what": "dig"}}).json()["result"].startswith("digging")
            )
            time.sleep(1.5)  # grass takes 0.9 s by hand; a button pressed meanwhile would end the dig (a new run)
            pressed = page.post(
                "press", json={"token": token, "primitive": "mineBlock", "args": ["red_mushroom_block", 1]}
            )
            assert pressed.json()["ok"]
        assert proc.wait(timeout=90) == 0
    finally:
        proc.kill()
    dug = [json.loads(line) for line in (run_dir / "episode_000" / "world_events.jsonl").read_text().splitlines()]
    dug = [e for e in dug if e.get("event") == "block_dug" and e.get("player") == "Ryn"]
    assert {"grass_block", "red_mushroom_block"} <= {e["block"] for e in dug}
    record = json.loads((run_dir / "episodes.jsonl").read_text().splitlines()[0])
    assert record["red_entrant"]["label"] == "do_nothing+human:alice"
