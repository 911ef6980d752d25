"""A person plays a real match from the page in a real headless Chromium (tests/support/cdp.py: keys and
mouse through the DevTools protocol) on a real server with real bots: sees the lobby's map, types a name,
presses Ready, turns with the mouse to a mushroom block, holds the left button until it breaks and holds W
to walk over its drop, looks down with the mouse and holds the left button to dig, presses T and sends
a teammate's signal that comes back on the page (and so does the Signal button's), sees its hud and
inventory, and its first-person view is served; a second page for the taken player is refused, the
page's token brings it back into its player, a primitive button runs. One short episode on the real
clock (people play on it) serves every check; the server's record shows each."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import httpx

from pillagerbench.people.relay import HUD_S
from tests.support.cdp import Browser
from tests.support.people import aim, events, frames, lobby, page_url

EPISODE_S = 18
SEED = 1  # the server's first drop roll of episode 0 (js/server/plugins/drops.js, seeded by it) gives a mushroom
CAP = (-6, 5, -8)  # a cap block of the red mushroom at (-5, -8), the nearest to Ryn's spawn (-7, -10): paper layout
CAP_CENTRE = (CAP[0] + 0.5, CAP[1] + 0.5, CAP[2] + 0.5)
WALK = 4.3  # blocks a second a walking player goes


def _match(run_dir: Path) -> subprocess.Popen:
    cmd = [sys.executable, "-m", "pillagerbench.cli", "run", "red=do_nothing", "red.humans=[Ryn]"]
    cmd += ["blue=do_nothing", f"episode_length={EPISODE_S}", f"run_dir={run_dir}", "display=plain"]
    cmd += ["humans.ready_timeout_s=120", "retries=0", f"seed={SEED}"]  # one episode, lagged or not (episode 0)
    return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=os.environ.copy())


def _mushroom(browser: Browser, hud: Callable[[], dict]) -> None:
    """The person turns to a cap block of the mushroom nearest Ryn's spawn with the mouse (closed loop on the
    hud's look), holds the left button until it breaks, then holds W to walk where it was, over its drop
    (seed 1: the episode's first drop roll gives a mushroom), and sees the mushroom in the hud."""
    at = aim(browser, hud, CAP_CENTRE)["position"]
    browser.hold(0.8)  # a mushroom block takes 0.3 s by hand
    browser.key("KeyW", "keyDown")
    time.sleep(math.hypot(CAP_CENTRE[0] - at["x"], CAP_CENTRE[2] - at["z"]) / WALK)  # as the look goes
    browser.key("KeyW", "keyUp")
    deadline = time.monotonic() + 3
    while "red_mushroom" not in hud()["items"] and time.monotonic() < deadline:
        time.sleep(0.1)


def _play(browser: Browser, hud: Callable[[], dict]) -> None:
    browser.wait_for("document.getElementById('board').textContent.startsWith('playing')")
    browser.click("main")  # pointer lock; the click itself digs at nothing (refused on the page)
    browser.wait_for("document.pointerLockElement === document.getElementById('main')")
    browser.wait_for("document.getElementById('vitals').textContent")  # the hud is read
    _mushroom(browser, hud)
    _dig_down(browser)


def _dig_down(browser: Browser) -> None:
    """The mouse down: the player looks at the ground under it; the left button held digs the grass."""
    browser.turn(0, 300)  # the page clamps the pitch at -1.5
    time.sleep(0.3)  # the look is sent 50 ms after the last move
    browser.hold(1.5)  # grass takes 0.9 s by hand; the button released ends the dig


def _chat(browser: Browser) -> None:
    """T lets the mouse go and opens the chat box; a teammate's signal typed there and sent with Enter comes
    back from the server onto the page (marked a signal), and so does the Signal button's; the hud shows
    health, food and the hotbar."""
    browser.key("KeyT", "keyDown")
    browser.key("KeyT", "keyUp")
    browser.wait_for("document.activeElement === document.getElementById('chat') && !document.pointerLockElement")
    browser.type(None, "[Raze signal]")
    browser.key("Enter", "keyDown")
    browser.key("Enter", "keyUp")
    signals = (
        "[...document.querySelectorAll('#chatlog .signal')].filter((e) => e.textContent.includes('[Raze signal]'))"
    )
    typed = browser.wait_for(f"{signals}.length")
    browser.click("signal")  # the Signal button, its teammate (Raze) chosen: the same line again
    browser.wait_for(f"{signals}.length > {typed}")
    assert browser.eval("document.getElementById('vitals').textContent") == "health 20 · food 20"
    assert browser.eval("document.querySelectorAll('#hotbar span').length") == 9


def _view(browser: Browser, url: str) -> None:
    """The page shows the first-person view the player's bot serves on loopback (js/bot/view.js): the
    viewer's page, and its stream (socket.io over HTTP polling) sends the world and the player's eyes."""
    src = browser.wait_for("document.getElementById('view').src")
    assert src.startswith("http://127.0.0.1:") and src != url
    with httpx.Client(base_url=src, timeout=10) as view:
        assert "Prismarine Viewer" in view.get("").text
        sid = json.loads(view.get("socket.io/", params={"EIO": 4, "transport": "polling"}).text[1:])["sid"]
        poll = {"EIO": 4, "transport": "polling", "sid": sid}
        view.post("socket.io/", params=poll, content="40")
        got = ""
        for _ in range(20):
            got += view.get("socket.io/", params=poll).text
            if '42["loadChunk"' in got and '"pitch"' in got:
                break
        view.post("socket.io/", params=poll, content="41")  # gone: the bot streams to the page's view only
    assert '42["version","1.16.4"]' in got and '42["loadChunk"' in got and '42["position"' in got


def _inventory(browser: Browser) -> str:
    """The inventory the page shows once the button's program is done."""
    browser.wait_for("document.getElementById('feed').textContent.includes('done: await mineBlock')")
    time.sleep(2 * HUD_S)  # the hud read after the program's end
    return browser.eval("document.getElementById('items').textContent")


def test_a_person_plays_from_a_browser(tmp_path: Path):
    run_dir = tmp_path / "run"
    browser = Browser()  # it starts while the match does
    proc = _match(run_dir)
    try:
        url = page_url(proc)
        token = lobby(browser, url)
        with httpx.Client(base_url=url, timeout=10) as page:
            second = page.post("join", json={"name": "mallory", "player": "Ryn"})
            assert second.status_code == 409 and "second page" in second.json()["error"]
            assert page.get("state", params={"token": token}).json()["seat"]["player"] == "Ryn"
            _play(browser, lambda: page.get("state", params={"token": token}).json()["hud"])
            _chat(browser)
            _view(browser, url)
            pressed = page.post(
                "press", json={"token": token, "primitive": "mineBlock", "args": ["red_mushroom_block", 1]}
            )
            assert pressed.json()["ok"]
            shown = _inventory(browser)
        assert proc.wait(timeout=60) == 0
    finally:
        proc.kill()
        browser.close()
    positions = frames(run_dir, "Ryn")
    assert abs(positions[-1][3] - positions[0][3]) + abs(positions[-1][1] - positions[0][1]) > 1.5, positions[-1]
    assert min(math.hypot(x - CAP_CENTRE[0], z - CAP_CENTRE[2]) for _, x, _, z, *_ in positions) < 1  # walked there
    world = events(run_dir)
    dug = [e for e in world if e.get("event") == "block_dug" and e.get("player") == "Ryn"]
    assert {"grass_block", "red_mushroom_block"} <= {e["block"] for e in dug}
    assert dug[0]["pos"] == list(CAP) and dug[0]["drops"], dug[0]  # the page's dig first, its drop
    got = next(i for i, e in enumerate(world) if e.get("event") == "item_picked_up" and e.get("player") == "Ryn")
    assert world[got]["item"] == "red_mushroom", world[got]
    assert got < world.index(dug[1]) and got < world.index(dug[2])  # before the grass and the button's mineBlock
    observed = [
        json.loads(line) for line in (run_dir / "episode_000" / "events" / "Ryn.jsonl").read_text().splitlines()
    ]
    inventory = [e[1]["inventory"] for e in observed if e[0] == "observe"][-1]
    assert shown == "inventory: " + (", ".join(f"{k} {v}" for k, v in sorted(inventory.items())) or "nothing")
    record = json.loads((run_dir / "episodes.jsonl").read_text().splitlines()[0])
    assert record["red_entrant"]["label"] == "do_nothing+human:alice"
