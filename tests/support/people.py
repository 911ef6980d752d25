"""What the people's tests read of a run (the page's address it prints, a player's replay frames, the server's
events, a bot's observations) and do on the page (the lobby, aiming the player's look with the mouse)."""

from __future__ import annotations

import gzip
import json
import math
import subprocess
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from tests.support.cdp import Browser


def page_url(proc: subprocess.Popen) -> str:
    """The people's page's address, from the run's output (`people: open URL to play`)."""
    assert proc.stdout is not None
    for line in proc.stdout:
        if line.startswith("people: open "):
            return line.split()[2]
    raise AssertionError("no page address printed")


def frames(run_dir: Path, player: str, episode: int = 0) -> list[list]:
    """`player`'s entries in the replay's frames of an episode."""
    with gzip.open(run_dir / f"episode_{episode:03d}" / "replay.jsonl.gz", "rt") as f:
        found = [json.loads(line) for line in f]
    return [p for f in found if f["type"] == "frame" for p in f["players"] if p[0] == player]


def events(run_dir: Path, episode: int = 0) -> list[dict]:
    """The server's record of an episode (world_events.jsonl)."""
    path = run_dir / f"episode_{episode:03d}" / "world_events.jsonl"
    return [json.loads(line) for line in path.read_text().splitlines()]


def observations(run_dir: Path, player: str, episode: int = 0) -> list[dict]:
    """`player`'s bot's own observations in an episode (events/PLAYER.jsonl), in order."""
    path = run_dir / f"episode_{episode:03d}" / "events" / f"{player}.jsonl"
    return [e[1] for e in map(json.loads, path.read_text().splitlines()) if e[0] == "observe"]


def shown(inventory: dict[str, int]) -> str:
    """An inventory as the page's hud writes it (`inventory: a 1, b 2` or `inventory: nothing`)."""
    return "inventory: " + (", ".join(f"{k} {v}" for k, v in sorted(inventory.items())) or "nothing")


def lobby(browser: Browser, url: str, name: str = "alice") -> str:
    """The person types a name, takes the seat and presses Ready; the page's token."""
    browser.open(url)
    browser.wait_for("document.getElementById('seat').options.length > 0")
    browser.wait_for("!!document.getElementById('map').contentDocument?.querySelector('canvas')")  # the map
    browser.type("name", name)
    browser.click("join")
    browser.wait_for("!document.getElementById('ready').disabled")
    browser.click("ready")
    return browser.eval("localStorage.getItem('pb-token')")


EYE = 1.62  # a player's eyes above its feet (mineflayer's entity height, as its lookAt)
TURN = 0.005  # radians the page turns the head per pixel of mouse movement (page.html)


def look_at(target: tuple[float, float, float], feet: dict) -> tuple[float, float]:
    """The yaw and pitch (mineflayer's: yaw 0 looks to -z and grows turning to -x; pitch up) from the eyes of a
    player whose feet are at `feet` ({x, y, z}) to the point `target`."""
    dx, dy, dz = target[0] - feet["x"], target[1] - feet["y"] - EYE, target[2] - feet["z"]
    return math.atan2(-dx, -dz), math.atan2(dy, math.hypot(dx, dz))


def aim(browser: Browser, hud: Callable[[], dict], target: tuple[float, float, float], tries: int = 8) -> dict:
    """Turn the player's head with the mouse (under pointer lock) until its hud says it looks at `target`:
    a closed loop on the hud (its look and position), each turn the error in pixels; the hud it ended on."""
    for _ in range(tries):
        now = hud()
        yaw, pitch = look_at(target, now["position"])
        dyaw = (yaw - now["yaw"] + math.pi) % (2 * math.pi) - math.pi
        if abs(dyaw) < 0.03 and abs(pitch - now["pitch"]) < 0.03:
            return now
        browser.turn(-dyaw / TURN, -(pitch - now["pitch"]) / TURN)
        deadline = time.monotonic() + 1.5  # the look is sent 50 ms after the moves, the hud read every 0.3 s
        while time.monotonic() < deadline:
            then = hud()
            if abs(then["yaw"] - now["yaw"]) + abs(then["pitch"] - now["pitch"]) > 0.01:
                time.sleep(0.35)  # the rest of the turn, if it was sent in two looks
                break
            time.sleep(0.1)
    raise AssertionError(f"the player does not look at {target} after {tries} turns: {hud()}")
