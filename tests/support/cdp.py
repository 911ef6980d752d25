"""Headless Chromium driven over the Chrome DevTools Protocol, for tests that press keys and click on a
page as a person would (tests/people/test_match.py).

The protocol runs over a pipe (`--remote-debugging-pipe`: Chromium reads commands on its fd 3 and writes
answers and events on its fd 4, each message JSON ended by a NUL byte), so only the standard library is
needed. Without a Chromium the test is skipped, or fails under CI=true (tests/support/browser.py).
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import tempfile
import threading
import time
from typing import Any

from tests.support.browser import chromium, flags

KEYS = {"KeyW": ("w", 87), "KeyA": ("a", 65), "KeyS": ("s", 83), "KeyD": ("d", 68), "Space": (" ", 32)}
KEYS |= {"KeyT": ("t", 84), "Enter": ("Enter", 13)}


class CdpError(RuntimeError):
    pass


class Browser:
    """One headless Chromium with one page; `call` sends a command to the page and returns its result."""

    def __init__(self, timeout: float = 20.0):
        self.timeout = timeout
        self.profile = tempfile.mkdtemp(prefix="pb-cdp-")
        to_chromium, self._out = os.pipe()
        self._in, from_chromium = os.pipe()
        shell = f'exec "$@" 3<&{to_chromium} 4>&{from_chromium}'  # bash: fd numbers past 9 too
        cmd = ["bash", "-c", shell, "bash", chromium(), *flags(self.profile), "--remote-debugging-pipe", "about:blank"]
        self.proc = subprocess.Popen(
            cmd, pass_fds=(to_chromium, from_chromium), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
        )
        os.close(to_chromium)
        os.close(from_chromium)
        self._next = 0
        self.at = (0.0, 0.0)  # where the mouse is
        self._answers: dict[int, dict] = {}
        self._cond = threading.Condition()
        threading.Thread(target=self._read, daemon=True).start()
        pages = [t for t in self.call("Target.getTargets", session=False)["targetInfos"] if t["type"] == "page"]
        attached = self.call(
            "Target.attachToTarget", {"targetId": pages[0]["targetId"], "flatten": True}, session=False
        )
        self.session = attached["sessionId"]

    def _read(self) -> None:
        buffer = b""
        while chunk := os.read(self._in, 65536):
            buffer += chunk
            *messages, buffer = buffer.split(b"\0")
            for raw in messages:
                message = json.loads(raw)
                if "id" in message:
                    with self._cond:
                        self._answers[message["id"]] = message
                        self._cond.notify_all()

    def call(self, method: str, params: dict | None = None, *, session: bool = True) -> dict:
        with self._cond:
            self._next += 1
            rid = self._next
        message: dict[str, Any] = {"id": rid, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = self.session
        os.write(self._out, json.dumps(message).encode() + b"\0")
        deadline = time.monotonic() + self.timeout
        with self._cond:
            while rid not in self._answers:
                if not self._cond.wait(max(0.0, deadline - time.monotonic())):
                    raise CdpError(f"{method}: no answer within {self.timeout:g} s")
            answer = self._answers.pop(rid)
        if "error" in answer:
            raise CdpError(f"{method}: {answer['error']}")
        return answer["result"]

    # ---- what a person does -------------------------------------------------------------------------------
    def open(self, url: str) -> None:
        self.call("Page.navigate", {"url": url})
        self.wait_for("document.readyState === 'complete' && !!document.getElementById('join')")

    def eval(self, expression: str) -> Any:
        result = self.call("Runtime.evaluate", {"expression": expression, "returnByValue": True, "awaitPromise": True})
        if "exceptionDetails" in result:
            raise CdpError(f"{expression}: {result['exceptionDetails']}")
        return result["result"].get("value")

    def wait_for(self, expression: str, timeout: float = 30.0) -> Any:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            value = self.eval(expression)
            if value:
                return value
            time.sleep(0.1)
        raise CdpError(f"not true within {timeout:g} s: {expression}")

    def centre(self, element_id: str) -> tuple[float, float]:
        box = self.eval(
            f"(() => {{ const r = document.getElementById({element_id!r}).getBoundingClientRect(); return [r.x + r.width / 2, r.y + r.height / 2] }})()"
        )
        return box[0], box[1]

    def centre_of(self, selector: str) -> tuple[float, float]:
        """The centre of the first element matching the CSS `selector`."""
        box = self.eval(
            f"(() => {{ const r = document.querySelector({selector!r}).getBoundingClientRect(); return [r.x + r.width / 2, r.y + r.height / 2] }})()"
        )
        return box[0], box[1]

    def click_on(self, selector: str) -> None:
        """A click on the first element matching the CSS `selector` (by its place on the page, as a person)."""
        x, y = self.centre_of(selector)
        self.mouse("mouseMoved", x, y)
        self.mouse("mousePressed", x, y)
        self.mouse("mouseReleased", x, y)

    def type_into(self, selector: str, text: str) -> None:
        """Click the field matching the CSS `selector`, then type `text` key by key."""
        self.click_on(selector)
        self.type(None, text)

    def turn(self, dx: float, dy: float, step: float = 20.0) -> None:
        """Mouse movement by (dx, dy) pixels from where the mouse is, in steps of at most `step` pixels: under
        pointer lock the page reads each move's movementX/Y (person.js: it turns the player's head)."""
        x, y = self.at
        n = max(1, int(max(abs(dx), abs(dy)) // step) + 1)
        for i in range(1, n + 1):
            self.mouse("mouseMoved", x + dx * i / n, y + dy * i / n)

    def mouse(self, kind: str, x: float, y: float, button: str = "left") -> None:
        self.at = (x, y)
        params: dict[str, Any] = {"type": kind, "x": x, "y": y, "button": button, "clickCount": 1}
        if kind == "mouseMoved":
            params["buttons"] = 0
        self.call("Input.dispatchMouseEvent", params)

    def click(self, element_id: str, hold: float = 0.0) -> None:
        x, y = self.centre(element_id)
        self.mouse("mouseMoved", x, y)
        self.mouse("mousePressed", x, y)
        time.sleep(hold)
        self.mouse("mouseReleased", x, y)

    def hold(self, seconds: float) -> None:
        """The left button held where the mouse is (no move: under pointer lock a move turns the head)."""
        x, y = self.at
        self.mouse("mousePressed", x, y)
        time.sleep(seconds)
        self.mouse("mouseReleased", x, y)

    def type(self, element_id: str | None, text: str) -> None:
        """Click `element_id` (None: where the keys go now), then type `text` key by key."""
        if element_id is not None:
            self.click(element_id)
        for char in text:
            self.call("Input.dispatchKeyEvent", {"type": "keyDown", "key": char, "text": char})
            self.call("Input.dispatchKeyEvent", {"type": "keyUp", "key": char})

    def key(self, code: str, kind: str) -> None:
        """`kind`: keyDown or keyUp of the key whose `code` is one of KEYS."""
        key, vk = KEYS[code]
        self.call("Input.dispatchKeyEvent", {"type": kind, "code": code, "key": key, "windowsVirtualKeyCode": vk})

    def close(self) -> None:
        self.proc.kill()
        self.proc.wait(timeout=10)
        for fd in (self._out, self._in):
            try:
                os.close(fd)
            except OSError:
                pass
        shutil.rmtree(self.profile, ignore_errors=True)
