"""People in the arena (issue 54): how fast a person's input reaches the server, how smoothly the page
runs, and what a person's bot costs beside an agent's. One real match on loopback, on the real clock:

    python benchmarks/people_latency.py [--presses 30] [--episode-length 120] [--no-webgl]

plays `pillagerbench run red=do_nothing 'red.humans=[Ryn]' blue=passive` in this process (the command's own
path, cli.commands.main) and, while the episode runs, from a thread:

(a) key to movement: a key-down for W (then S, alternately, so the player stays where it was) POSTed to
    the page's input endpoint (`act`, as page.html sends it) and the time until the server sees the
    player move, read by polling the server's own view of the players (the control channel's `players`
    op) back to back; median and 95th percentile over --presses presses of each key; the same for a few
    key presses in headless Chromium (tests/support/cdp.py: the DevTools protocol's key event on the page);
(b) the page's frames per second in headless Chromium (requestAnimationFrame callbacks over a few
    seconds): the lobby with the map, the game with the first-person view's frame (and inside that frame),
    and without it; WebGL drawn in software (SwiftShader) unless --no-webgl;
(c) the CPU each bot process took (psutil): the person's (Ryn) beside the agents' (Raze: do_nothing,
    Byte and Blink: passive) and the server's, over the presses, over the browser's part and over the
    whole game.

The issue's target: input reaches the server within 100 ms on loopback. Figures: docs/people.md.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import statistics
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

import httpx
import psutil

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from pillagerbench.cli import commands
from pillagerbench.people.page import PageServer
from pillagerbench.server import ArenaServer

PERSON = "Ryn"
KEYS = {"KeyW": "forward", "KeyS": "back"}
FPS_JS = """new Promise((done) => { let n = 0; const t0 = performance.now()
  const f = (t) => { n++; if (t - t0 < %d) requestAnimationFrame(f); else done(n * 1000 / (t - t0)) }
  requestAnimationFrame(f) })"""


class Hooks:
    """What the benchmark reads from the match it runs in this process: the server, its loop, the page."""

    def __init__(self) -> None:
        self.server: ArenaServer | None = None
        self.loop: asyncio.AbstractEventLoop | None = None
        self.url = ""
        self.page_up = threading.Event()

    def install(self) -> None:
        server_start, page_start = ArenaServer.start, PageServer.start
        hooks = self

        async def start_server(self: ArenaServer, *args: Any, **kwargs: Any) -> ArenaServer:
            hooks.server, hooks.loop = self, asyncio.get_running_loop()
            return await server_start(self, *args, **kwargs)

        async def start_page(self: PageServer) -> str:
            hooks.url = await page_start(self)
            hooks.page_up.set()
            return hooks.url

        ArenaServer.start = start_server  # type: ignore[method-assign]
        PageServer.start = start_page  # type: ignore[method-assign]

    async def position(self) -> tuple[float, float]:
        """The person's player's (x, z) as the server has it (the control channel's `players` op)."""
        assert self.server is not None and self.loop is not None
        future = asyncio.run_coroutine_threadsafe(self.server.request("players"), self.loop)
        for p in await asyncio.wrap_future(future):
            if p["name"] == PERSON:
                return p["pos"][0], p["pos"][2]
        raise RuntimeError(f"{PERSON} is not online")


# ---- (c) CPU ---------------------------------------------------------------------------------------------
def processes() -> dict[str, psutil.Process]:
    """This process's node children: each bot by its player's name (its settings' `username`), the server."""
    out: dict[str, psutil.Process] = {}
    for proc in psutil.Process().children(recursive=True):
        try:
            cmd = proc.cmdline()
        except psutil.Error:
            continue
        if cmd and cmd[-1].startswith("{") and '"username"' in cmd[-1]:
            out[json.loads(cmd[-1])["username"]] = proc
        elif any(part.endswith("server/main.js") for part in cmd):
            out["server"] = proc
    return out


def cpu_mark(procs: dict[str, psutil.Process]) -> tuple[float, dict[str, float]]:
    seconds = {}
    for name, proc in procs.items():
        try:
            times = proc.cpu_times()
            seconds[name] = times.user + times.system
        except psutil.Error:
            pass
    return time.monotonic(), seconds


def cpu_share(a: tuple[float, dict[str, float]], b: tuple[float, dict[str, float]]) -> dict[str, float]:
    """Per process, the % of one core it took between the marks `a` and `b`."""
    wall = b[0] - a[0]
    return {k: 100 * (b[1][k] - a[1][k]) / wall for k in a[1] if k in b[1] and wall > 0}


# ---- (a) key to movement ---------------------------------------------------------------------------------
async def settled(hooks: Hooks) -> tuple[float, float]:
    """The player's position once the server has seen it still for 0.3 s (a released key slides on)."""
    last, since = await hooks.position(), time.monotonic()
    while time.monotonic() - since < 0.3:
        await asyncio.sleep(0.05)
        now = await hooks.position()
        if abs(now[0] - last[0]) + abs(now[1] - last[1]) > 1e-4:
            last, since = now, time.monotonic()
    return last


async def moved_after(hooks: Hooks, start: tuple[float, float], t0: float, timeout: float = 2.0) -> tuple[float, int]:
    """Seconds from `t0` until the server has the player away from `start`; and how many reads it took.
    The reads go back to back (each a round trip to the server through the match's loop)."""
    reads = 0
    while time.perf_counter() - t0 < timeout:
        x, z = await hooks.position()
        reads += 1
        if abs(x - start[0]) + abs(z - start[1]) > 1e-4:
            return time.perf_counter() - t0, reads
    raise TimeoutError


async def presses(hooks: Hooks, down, up, count: int) -> dict[str, Any]:
    """`count` presses of each key (W, then S, alternately): down(key) at t0, the server's first sight of
    the player moving, up(key); the latencies (ms) and the read resolution."""
    out: dict[str, Any] = {"ms": [], "missed": 0, "reads": [], "answered": []}

    async def timed(t0: float, key: str) -> float:
        await down(key)
        return time.perf_counter() - t0

    for i in range(2 * count):
        key = list(KEYS)[i % 2]
        start = await settled(hooks)
        t0 = time.perf_counter()
        sent = asyncio.ensure_future(timed(t0, key))
        try:
            seconds, reads = await moved_after(hooks, start, t0)
            out["ms"].append(1000 * seconds)
            out["reads"].append(1000 * seconds / reads)
        except TimeoutError:
            out["missed"] += 1
        out["answered"].append(1000 * await sent)  # the input's own round trip (POST: the bot's act op done)
        await up(key)
    return out


def summary(ms: list[float]) -> dict[str, float]:
    if not ms:
        return {}
    ordered = sorted(ms)
    p95 = ordered[min(len(ordered) - 1, round(0.95 * (len(ordered) - 1)))]
    return {"n": len(ms), "median": statistics.median(ms), "p95": p95, "max": ordered[-1]}


async def http_presses(hooks: Hooks, token: str, count: int) -> dict[str, Any]:
    async with httpx.AsyncClient(base_url=hooks.url, timeout=10) as page:

        async def act(controls: dict[str, bool]) -> None:
            answer = await page.post("act", json={"token": token, "input": {"what": "controls", "controls": controls}})
            answer.raise_for_status()

        return await presses(hooks, lambda key: act({KEYS[key]: True}), lambda key: act({}), count)


# ---- (b) the page in headless Chromium --------------------------------------------------------------------
def fps(browser, seconds: float = 4.0) -> float:
    return round(browser.eval(FPS_JS % round(seconds * 1000)), 1)


def frame_fps(browser, src: str, seconds: float = 4.0) -> Any:
    """The frames per second inside the first-person view's frame (the viewer's page, another port), and
    whether it drew with WebGL: evaluated in that frame (an isolated world: its DOM, its animation frames)."""
    frames = [browser.call("Page.getFrameTree")["frameTree"]]
    while frames and not frames[0]["frame"].get("url", "").startswith(src):
        frames = frames[1:] + frames[0].get("childFrames", [])
    if not frames:
        return "no frame"
    world = browser.call("Page.createIsolatedWorld", {"frameId": frames[0]["frame"]["id"]})["executionContextId"]
    expression = f"Promise.all([{FPS_JS % round(seconds * 1000)}, !!document.querySelector('canvas')])"
    params = {"expression": expression, "contextId": world, "awaitPromise": True, "returnByValue": True}
    rate, canvas = browser.call("Runtime.evaluate", params)["result"]["value"]
    return f"{rate:.1f} ({'a canvas' if canvas else 'no canvas'})"


def webgl_flags() -> None:
    """Chromium with WebGL drawn in software (SwiftShader), so the first-person view draws a picture:
    tests/support/browser.py's flags turn the GPU off, which leaves no WebGL."""
    from tests.support import cdp

    base = cdp.flags
    cdp.flags = lambda profile: (
        [f for f in base(profile) if f != "--disable-gpu"]
        + [
            "--use-angle=swiftshader",
            "--enable-unsafe-swiftshader",
        ]
    )


def lobby_fps(browser, url: str, token: str) -> dict[str, Any]:
    """The lobby with the map: the page opened with the seat's token (as the person's own page)."""
    browser.open(url)
    browser.eval(f"localStorage.setItem('pb-token', {json.dumps(token)})")
    browser.open(url)
    browser.wait_for("!!document.getElementById('map').contentDocument?.querySelector('canvas')")
    return {"lobby (map)": fps(browser)}


def game_fps(browser, hooks: Hooks, url: str, count: int) -> dict[str, Any]:
    """The game's page: with the first-person view's frame (if it loads), without it; then key presses
    in Chromium (the DevTools protocol's key events on the page) to the server's sight of the move."""
    browser.open(url)
    browser.wait_for("document.getElementById('board').textContent.startsWith('playing')")
    out: dict[str, Any] = {"webgl": browser.eval("!!document.createElement('canvas').getContext('webgl')")}
    view = browser.wait_for("document.getElementById('view').src || document.getElementById('viewmsg').textContent")
    out["view"] = view
    if view.startswith("http"):
        time.sleep(5.0)  # the viewer's page loads and its stream starts
        out["game, with the 3D view"] = fps(browser)
        out["the 3D view's own frame"] = frame_fps(browser, view)
        browser.eval("document.getElementById('view').src = 'about:blank'")
    out["game, without the 3D view"] = fps(browser)

    async def key(code: str, kind: str) -> None:
        await asyncio.to_thread(browser.key, code, kind)

    keyed = asyncio.run(presses(hooks, lambda k: key(k, "keyDown"), lambda k: key(k, "keyUp"), count))
    out["keys"] = keyed
    return out


# ---- the driver -----------------------------------------------------------------------------------------
def state(url: str, token: str = "") -> dict[str, Any]:
    return httpx.get(url + "state", params={"token": token}, timeout=10).json()


def playing(url: str) -> bool:
    try:
        return state(url)["phase"] == "playing"
    except httpx.HTTPError:  # the page is gone: the match is over
        return False


def drive(hooks: Hooks, args: argparse.Namespace, out: dict[str, Any]) -> None:
    """The person's side of the benchmark, from a thread while the match plays in the main one."""
    from tests.support.cdp import Browser

    hooks.page_up.wait()
    url = hooks.url
    token = httpx.post(url + "join", json={"name": "bench", "player": PERSON}, timeout=10).json()["result"]["token"]
    browser = Browser(timeout=30)
    try:
        out["fps"] = lobby_fps(browser, url, token)
        browser.call("Page.navigate", {"url": "about:blank"})  # no page during the presses: the endpoint alone
        httpx.post(url + "ready", json={"token": token}, timeout=10)
        while state(url)["phase"] != "playing":
            time.sleep(0.05)
        procs = processes()
        marks = {"start": cpu_mark(procs)}
        out["http"] = asyncio.run(http_presses(hooks, token, args.presses))
        marks["presses"] = cpu_mark(procs)
        out["fps"] |= game_fps(browser, hooks, url, args.browser_presses)
        marks["browser"] = cpu_mark(procs)
    finally:
        browser.close()
    marks["end"] = marks["browser"]
    while playing(url):
        marks["end"] = cpu_mark(procs)
        time.sleep(0.25)
    out["cpu"] = {
        "presses over HTTP": cpu_share(marks["start"], marks["presses"]),
        "page open in Chromium": cpu_share(marks["presses"], marks["browser"]),
        "the whole game": cpu_share(marks["start"], marks["end"]),
    }


def table(out: dict[str, Any]) -> str:
    lines = ["(a) key down to the server's sight of the move (ms)"]
    lines.append("  how          n  median    p95    max  missed  ms/read  answered (median, p95)")
    for label, got in (("POST act", out.get("http")), ("Chromium key", (out.get("fps") or {}).get("keys"))):
        s = summary((got or {}).get("ms", []))
        if s:
            read, answered = statistics.median(got["reads"]), summary(got["answered"])
            lines.append(
                f"  {label:<12} {s['n']:>2} {s['median']:>7.1f} {s['p95']:>6.1f} {s['max']:>6.1f} {got['missed']:>7}"
                f" {read:>8.1f}  {answered['median']:.1f}, {answered['p95']:.1f}"
            )
    lines.append("(b) the page's frames per second (headless Chromium, requestAnimationFrame)")
    for k, v in (out.get("fps") or {}).items():
        if k != "keys":
            lines.append(f"  {k}: {v}")
    lines.append("(c) CPU, % of one core")
    cpu = out.get("cpu") or {}
    names = sorted({n for v in cpu.values() for n in v}, key=lambda n: (n != PERSON, n == "server", n))
    lines.append("  " + " " * 22 + "".join(f"{n:>9}" for n in names))
    for window, shares in cpu.items():
        lines.append(f"  {window:<22}" + "".join(f"{shares.get(n, float('nan')):>9.1f}" for n in names))
    return "\n".join(lines)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--presses", type=int, default=30, help="presses of each key (W, S) over the endpoint")
    p.add_argument("--browser-presses", type=int, default=10, help="presses of each key in Chromium")
    p.add_argument("--episode-length", type=int, default=120)
    p.add_argument("--json", metavar="PATH", help="also write the figures as JSON")
    p.add_argument("--no-webgl", action="store_true", help="Chromium without WebGL (as the tests run it)")
    args = p.parse_args()
    if not args.no_webgl:
        webgl_flags()
    hooks, out = Hooks(), {"load_before": os.getloadavg(), "cores": os.cpu_count()}
    hooks.install()
    driver = threading.Thread(target=drive, args=(hooks, args, out), daemon=True)
    driver.start()
    with tempfile.TemporaryDirectory(prefix="pb-people-bench-") as tmp:
        argv = ["run", "red=do_nothing", f"red.humans=[{PERSON}]", "blue=passive", "display=plain", "retries=0"]
        argv += [f"episode_length={args.episode_length}", f"run_dir={tmp}/run", "humans.ready_timeout_s=120"]
        code = commands.main(argv)
        driver.join(timeout=30)
        episodes = Path(tmp) / "run" / "episodes.jsonl"
        out["run"] = json.loads(episodes.read_text().splitlines()[0])["status"] if episodes.exists() else "none"
    out["load_after"] = os.getloadavg()
    print(
        f"match exit {code}, episode {out['run']}; load {out['load_before']} -> {out['load_after']}, {out['cores']} cores"
    )
    print(table(out))
    if args.json:
        Path(args.json).write_text(json.dumps(out, indent=1, default=str))
    return 0 if code == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
