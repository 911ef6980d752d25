"""Headless Chromium for the browser tests: open a page, let its scripts run, read the DOM back.

Tests that need a browser call `chromium()` first: without a Chromium on PATH they are skipped
with the reason, except under CI=true, where they fail (CI installs Debian's `chromium`).
"""

from __future__ import annotations

import html
import json
import os
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

import pytest

NAMES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
RESULT_ID = "test-result"


def chromium() -> str:
    for name in NAMES:
        path = shutil.which(name)
        if path:
            return path
    reason = f"no Chromium on PATH (looked for {', '.join(NAMES)}; Debian: apt-get install chromium)"
    if os.environ.get("CI", "").lower() == "true":
        pytest.fail(f"CI=true: {reason}")
    pytest.skip(reason)


def flags(profile: str) -> list[str]:
    return [
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--no-first-run",
        "--disable-extensions",
        "--disable-background-networking",
        "--mute-audio",
        f"--user-data-dir={profile}",
        "--window-size=1400,1000",
    ]


def dump_dom(
    url: str, *, budget_ms: int = 5000, timeout: float = 90, extra: list[str] | None = None
) -> tuple[str, str]:
    """The DOM after the page ran (virtual time `budget_ms`), and Chromium's log (console lines)."""
    return headless(url, [*(extra or []), "--dump-dom"], budget_ms, timeout)


def headless(url: str, args: list[str], budget_ms: int, timeout: float) -> tuple[str, str]:
    """Run headless Chromium on `url` with `args` for `budget_ms` of virtual time; its stdout and log."""
    with tempfile.TemporaryDirectory(prefix="pb-chromium-") as profile:
        cmd = [
            chromium(),
            *flags(profile),
            "--enable-logging=stderr",
            "--v=0",
            f"--virtual-time-budget={budget_ms}",
            *args,
            url,
        ]
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    return done.stdout, done.stderr


def console_errors(log: str) -> list[str]:
    """Console messages that report errors (uncaught exceptions, console.error, errors logged) from
    Chromium's log."""
    return [
        line
        for line in log.splitlines()
        if ":CONSOLE" in line and ("Uncaught" in line or "ERROR:CONSOLE" in line or "Error" in line)
    ]


def run_test_script(page: Path, script: str, **kw) -> dict:
    """Open a copy of `page` with `script` appended; the script puts JSON into
    `<pre id="test-result">`, which is returned (with the console errors under "console_errors")."""
    copy = page.with_name(page.stem + ".test.html")
    text = page.read_text()
    copy.write_text(text.replace("</body></html>", f"<script>{script}</script></body></html>"))
    dom, log = dump_dom(copy.resolve().as_uri(), **kw)
    m = re.search(rf'<pre id="{RESULT_ID}">(.*?)</pre>', dom, re.S)
    assert m, f"the page wrote no test result; console: {console_errors(log) or log[-2000:]}"
    result = json.loads(html.unescape(m.group(1)))
    result["console_errors"] = console_errors(log)
    return result


WEBGL = ["--use-angle=swiftshader", "--enable-unsafe-swiftshader"]  # software WebGL, no GPU needed


def screenshot(url: str, path: Path, *, budget_ms: int = 10000, timeout: float = 120) -> str:
    """A PNG of the page after `budget_ms` of (virtual) time, with software WebGL; returns Chromium's log."""
    return headless(url, [*WEBGL, f"--screenshot={path}"], budget_ms, timeout)[1]
