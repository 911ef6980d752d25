"""The replay page in a real browser (headless Chromium), from a recorded episode (the fixture: a
30 s Mushroom War episode, passive vs balanced): the map is drawn, the markers move with the time
cursor, the chat feed shows the episode's lines at their times."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from pillagerbench.replay.page import write_replay
from pillagerbench.replay.read import load_replay
from tests.support.browser import chromium, run_test_script

FIXTURE = Path(__file__).with_name("fixtures") / "episode_000"

CHECKS = """
(function () {
  const r = window.replay
  const out = { duration: r.duration }
  const map = document.getElementById('map')
  const slider = document.getElementById('time')
  function pixels () {
    const d = map.getContext('2d').getImageData(0, 0, map.width, map.height).data
    let drawn = 0; const colours = new Set()
    for (let i = 0; i < d.length; i += 4) {
      if (d[i + 3] > 0 && !(d[i] === 255 && d[i + 1] === 255 && d[i + 2] === 255)) drawn++
      colours.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2])
    }
    let hash = 0  // of every pixel, to tell two pictures apart
    for (let i = 0; i < d.length; i++) hash = (Math.imul(hash, 31) + d[i]) | 0
    return { drawn, total: d.length / 4, colours: colours.size, hash }
  }
  function at (t) {  // move the time cursor as a person would: the slider's input event
    slider.value = t
    slider.dispatchEvent(new Event('input'))
    return { t: r.time(), markers: r.markers(), feed: r.visibleFeed(), pixels: pixels() }
  }
  out.early = at(%EARLY%)
  out.late = at(%LATE%)
  out.end = at(r.duration)
  const pre = document.createElement('pre'); pre.id = 'test-result'; pre.textContent = JSON.stringify(out)
  document.body.append(pre)
})()
"""


@pytest.fixture(scope="module")
def page(tmp_path_factory) -> Path:
    chromium()
    episode = tmp_path_factory.mktemp("replay") / "episode_000"
    shutil.copytree(FIXTURE, episode)
    out, _ = write_replay(episode)
    return out


def chat_until(t: float) -> list[str]:
    """The chat lines of the recording up to time t, as the page writes them."""
    lines = []
    for r in load_replay(FIXTURE).records:
        if r.get("type") == "event" and r["event"].get("event") == "chat" and r["t"] <= t:
            who = r["event"].get("player")
            lines.append((f"<{who}> " if who else "[server] ") + r["event"]["message"])
    return lines


def test_replay_page_draws_the_map_moves_markers_and_syncs_the_chat(page):
    early, late = 3.0, 25.0
    result = run_test_script(page, CHECKS.replace("%EARLY%", str(early)).replace("%LATE%", str(late)))
    assert result["console_errors"] == []
    a, b, end = result["early"], result["late"], result["end"]
    # the map: most of the canvas drawn, in several block colours
    assert a["pixels"]["drawn"] > 0.9 * a["pixels"]["total"], a["pixels"]
    assert a["pixels"]["colours"] >= 4, a["pixels"]
    # every player has a marker, and markers moved between the two times
    assert set(a["markers"]) == {"Ryn", "Raze", "Byte", "Blink"}
    moved = [n for n in a["markers"] if a["markers"][n] != b["markers"][n]]
    assert len(moved) >= 2, (a["markers"], b["markers"])
    assert a["pixels"]["hash"] != b["pixels"]["hash"]  # the picture changed too, not only the markers' state
    # the feed shows exactly the lines up to the cursor, chat among them, in time order
    for state, t in ((a, early), (b, late)):
        assert all(ft <= t for ft, _ in state["feed"]), state["feed"]
        shown_chat = [text for _, text in state["feed"] if "<" in text or "[server]" in text]
        for line in chat_until(t):
            assert any(line in text for text in shown_chat), (line, shown_chat)
    assert len(b["feed"]) > len(a["feed"])
    # at the end, every line of the episode's chat.txt is there
    chat_txt = (FIXTURE / "chat.txt").read_text().splitlines()
    assert chat_txt
    for line in chat_txt:
        assert any(line in text for _, text in end["feed"]), line
