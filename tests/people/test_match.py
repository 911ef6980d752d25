"""A person plays a real match from the page in a real headless Chromium (tests/support/cdp.py: keys and
mouse through the DevTools protocol) on a real server with real bots: sees the lobby's map, types a name,
presses Ready, holds W, looks down with the mouse and holds the left button to dig, presses T and sends
a teammate's signal that comes back on the page (and so does the Signal button's), sees its hud and
inventory, and its first-person view is served; a second page for the taken player is refused, the
page's token brings it back into its player, a primitive button runs. One short episode on the real
clock (people play on it) serves every check; the server's record shows each."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import httpx

from pillagerbench.people.relay import HUD_S
from tests.support.cdp import Browser
from tests.support.people import frames, page_url

EPISODE_S = 12


def _match(run_dir: Path) -> subprocess.Popen:
    cmd = [sys.executable, "-m", "pillagerbench.cli", "run", "red=do_nothing", "red.humans=[Ryn]"]
    cmd += ["blue=do_nothing", f"episode_length={EPISODE_S}", f"run_dir={run_dir}", "display=plain"]
    cmd += ["humans.ready_timeout_s=120", "retries=0"]  # one episode, lagged or not (the checks read episode 0)
    return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=os.environ.copy())


def _lobby(browser: Browser, url: str) -> str:
    """The person types a name, takes the seat and presses Ready; the page's token."""
    browser.open(url)
    browser.wait_for("document.getElementById('seat').options.length > 0")
    browser.wait_for("!!document.getElementById('map').contentDocument?.querySelector('canvas')")  # the map
    browser.type("name", "alice")
    browser.click("join")
    browser.wait_for("!document.getElementById('ready').disabled")
    browser.click("ready")
    return browser.eval("localStorage.getItem('pb-token')")


def _walk_and_dig(browser: Browser) -> None:
    browser.wait_for("document.getElementById('board').textContent.startsWith('playing')")
    browser.click("main")  # pointer lock; the click itself digs at nothing (refused on the page)
    browser.wait_for("document.pointerLockElement === document.getElementById('main')")
    browser.key("KeyW", "keyDown")
    time.sleep(1.0)
    browser.key("KeyW", "keyUp")
    x, y = browser.centre("main")
    for step in range(1, 11):  # the mouse down: the player looks at the ground before it
        browser.mouse("mouseMoved", x, y + 20 * step)
    time.sleep(0.3)  # the look is sent 50 ms after the last move
    browser.click("main", hold=1.5)  # grass takes 0.9 s by hand; the button released ends the dig


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
        token = _lobby(browser, url)
        with httpx.Client(base_url=url, timeout=10) as page:
            second = page.post("join", json={"name": "mallory", "player": "Ryn"})
            assert second.status_code == 409 and "second page" in second.json()["error"]
            assert page.get("state", params={"token": token}).json()["seat"]["player"] == "Ryn"
            _walk_and_dig(browser)
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
    events = [json.loads(line) for line in (run_dir / "episode_000" / "world_events.jsonl").read_text().splitlines()]
    dug = [e for e in events if e.get("event") == "block_dug" and e.get("player") == "Ryn"]
    assert {"grass_block", "red_mushroom_block"} <= {e["block"] for e in dug}
    observed = [
        json.loads(line) for line in (run_dir / "episode_000" / "events" / "Ryn.jsonl").read_text().splitlines()
    ]
    inventory = [e[1]["inventory"] for e in observed if e[0] == "observe"][-1]
    assert shown == "inventory: " + (", ".join(f"{k} {v}" for k, v in sorted(inventory.items())) or "nothing")
    record = json.loads((run_dir / "episodes.jsonl").read_text().splitlines()[0])
    assert record["red_entrant"]["label"] == "do_nothing+human:alice"
