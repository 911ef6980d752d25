"""A person plays a real Dash & Dine match from the page in headless Chromium (tests/support/cdp.py): takes
Ryn's seat and, in the game, types into the chest buttons' fields and clicks them: getItemFromChest takes 3
buckets from the bucket chest beside Ryn's spawn (the paper's layout: the chest at (-7, 4, -7) holds 16
buckets; Ryn stands at (-5, 4, -10), within reach of it: no walk), depositItemIntoChest puts 1 back. The
records show each: Ryn's bot saw the chest hold 13 buckets, then 14 at the end, and Ryn hold 2
(events/Ryn.jsonl), which is the inventory the page shows."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from tests.support.cdp import Browser
from tests.support.people import lobby, observations, page_url, shown

EPISODE_S = 12
CHEST = "-7,4,-7"  # the bucket chest (dash_and_dine_layout: bucket_chest at (-7, -7), on the floor)


def _match(run_dir: Path) -> subprocess.Popen:
    cmd = [sys.executable, "-m", "pillagerbench.cli", "run", "scenario=dash_and_dine", "red=do_nothing"]
    cmd += ["red.humans=[Ryn]", "blue=do_nothing", f"episode_length={EPISODE_S}", f"run_dir={run_dir}"]
    cmd += ["display=plain", "humans.ready_timeout_s=120", "retries=0"]  # the checks read episode 0
    return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=os.environ.copy())


def _press(browser: Browser, primitive: str, *args: str) -> None:
    """The person types the button's arguments into its fields and clicks it; its program's end in the feed."""
    for i, text in enumerate(args):
        browser.type_into(f"#press-{primitive} ~ input:nth-of-type({i + 1})", text)
    browser.click(f"press-{primitive}")
    browser.wait_for(f"document.getElementById('feed').textContent.includes('done: await {primitive}(')")


def test_a_person_uses_the_chest_buttons(tmp_path: Path):
    run_dir = tmp_path / "run"
    browser = Browser()  # it starts while the match does
    proc = _match(run_dir)
    try:
        lobby(browser, page_url(proc))
        browser.wait_for("document.getElementById('board').textContent.startsWith('playing')")
        browser.wait_for("!!document.getElementById('press-depositItemIntoChest')")
        _press(browser, "getItemFromChest", CHEST, '{"bucket": 3}')
        _press(browser, "depositItemIntoChest", CHEST, '{"bucket": 1}')
        assert "refused" not in browser.eval("document.getElementById('feed').textContent")
        items = "document.getElementById('items').textContent"
        page = browser.wait_for(f"{items}.endsWith('bucket 2') && {items}", timeout=5)  # the hud after the chest
        assert proc.wait(timeout=60) == 0
    finally:
        proc.kill()
        browser.close()
    seen = observations(run_dir, "Ryn")
    chests = [o["nearbyChests"].get("(-7, 4, -7)") for o in seen]
    assert {"bucket": 13} in chests and chests[-1] == {"bucket": 14}, chests
    assert seen[-1]["inventory"] == {"bucket": 2} and page == shown(seen[-1]["inventory"]), (page, seen[-1])
