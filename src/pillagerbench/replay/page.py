"""`pillagerbench replay EPISODE_DIR`: one self-contained HTML page (`replay.html` in the episode's
directory; the page's script and style are inline, it loads nothing) from the episode's recording.

    pillagerbench replay runs/2026-11-23_mushroom_war_passive_vs_balanced/episode_000
"""

from __future__ import annotations

import html
import json
import sys
from importlib import resources
from pathlib import Path

from pillagerbench.replay.read import Replay, ReplayError, load_replay
from pillagerbench.replay.record import GROUND_Y
from pillagerbench.rundir.names import REPLAY_PAGE

PAGE = REPLAY_PAGE  # the page beside an episode's recording (rundir/names.py)

STYLE = """
body { font-family: system-ui, sans-serif; margin: 1em; color: #222; }
h1 { font-size: 1.3em; margin: 0 0 0.3em; } .note { color: #555; font-size: 0.9em; } .warn { color: #a33; }
#grid { display: grid; grid-template-columns: auto minmax(320px, 1fr); gap: 1em; align-items: start; }
#map { border: 1px solid #999; image-rendering: pixelated; }
#controls { display: flex; gap: 0.6em; align-items: center; margin: 0.5em 0; }
#time { flex: 1; min-width: 300px; } #clock { font-variant-numeric: tabular-nums; min-width: 8em; }
#legend { display: flex; flex-wrap: wrap; gap: 0.3em 1em; font-size: 0.8em; max-width: 780px; }
#legend i { display: inline-block; width: 0.9em; height: 0.9em; margin-right: 0.3em; vertical-align: middle;
  border: 1px solid #0006; }
#legend i.pl { border-radius: 50%; background: #e53935; } #legend i.it { background: #fff; border-color: #000; }
#legend i.mob { background: #f4c2c2; }
#feed { height: 330px; overflow-y: auto; border: 1px solid #ccc; font-size: 0.85em; padding: 0.3em; }
.ev { padding: 1px 3px; cursor: pointer; } .ev b { font-weight: normal; color: #777; margin-right: 0.4em; }
.ev.chat { color: #000; } .ev.program { color: #2a6; } .ev.error { color: #c22; } .ev.world { color: #666; }
.ev.now { background: #fff3b0; }
table { border-collapse: collapse; font-size: 0.85em; } td, th { border: 1px solid #ddd; padding: 1px 6px; }
"""

BODY = """
<h1>{title}</h1>
<p class="note">{subtitle}</p>{warning}
<div id="grid">
 <div>
  <canvas id="map"></canvas>
  <div id="controls"><button id="play">▶ play</button>
   <label>speed <select id="speed"><option>0.5</option><option selected>1</option><option>2</option>
    <option>4</option><option>8</option><option>16</option></select></label>
   <input id="time" type="range" min="0" step="0.1" value="0"><span id="clock"></span></div>
  <div id="legend"></div>
 </div>
 <div>
  <h3>Scores</h3><canvas id="scores" width="460" height="180"></canvas><div id="score-now" class="note"></div>
  <h3>Players</h3><table><thead><tr><th>player</th><th>side</th><th>held</th><th>x, y, z</th><th>runs</th>
   <th>errors</th></tr></thead><tbody id="players"></tbody></table>
  <h3>Chat and events</h3><div id="feed"></div>
 </div>
</div>
"""

# server events shown in the feed (the rest stay in the recording): event -> text
WORLD_EVENTS = {
    "block_dug": lambda e: f"{e.get('player')} dug {e.get('block', 'a block')}",
    "item_picked_up": lambda e: (
        f"{e.get('player')} picked up {e.get('count', 1)} {e.get('item')}"
        + (f" (thrown by {e['thrower']})" if e.get("thrower") else "")
    ),
    "item_tossed": lambda e: f"{e.get('player')} tossed {e.get('count', 1)} {e.get('item')}",
    "item_crafted": lambda e: f"{e.get('player')} crafted {e.get('count', 1)} {e.get('item')}",
    "mob_killed": lambda e: f"{e.get('player')} killed {e.get('mob', 'a mob')}",
    "planted": lambda e: f"{e.get('player')} planted {e.get('block')}",
    "berries_harvested": lambda e: f"{e.get('player')} harvested {e.get('count')} berries",
    "cow_milked": lambda e: f"{e.get('player')} milked a cow",
    "refused": lambda e: f"server refused {e.get('player')}: {e.get('action')} ({e.get('reason')})",
    "player_left": lambda e: f"{e.get('player')} left",
    "player_joined": lambda e: f"{e.get('player')} joined",
}


def page_data(replay: Replay) -> dict:
    """What the page's script draws, from the recording's records (docs/replays.md)."""
    h = replay.header
    tracks: dict[str, list] = {}
    changes, feed, scores = [], [], []
    items: dict[int, dict] = {}
    item_list: list[dict] = []
    mobs: dict[int, dict] = {}
    mob_list: list[dict] = []
    programs: dict[str, list] = {}
    blocks = {"box": [[0, GROUND_Y, 0], [15, GROUND_Y, 15]], "palette": [], "blocks": []}
    end = replay.duration
    for r in replay.records:
        kind, t = r.get("type"), r.get("t", 0)
        if kind == "blocks":
            blocks = {"box": r["box"], "palette": r["palette"], "blocks": r["blocks"]}
        elif kind == "frame":
            for name, x, y, z, yaw, _pitch, held in r["players"]:
                tracks.setdefault(name, []).append([t, x, y, z, yaw, held])
        elif kind == "blocks_changed":
            changes += [[t, *b] for b in r["blocks"]]
        elif kind == "item":
            old = items.get(r["id"])
            if old:
                old["to"] = t
            items[r["id"]] = {"item": r["item"], "count": r["count"], "pos": r["pos"], "from": t, "to": end + 1}
            item_list.append(items[r["id"]])
        elif kind == "item_gone":
            if r["id"] in items:
                items.pop(r["id"])["to"] = t
        elif kind == "mob":
            old = mobs.get(r["id"])
            if old:
                old["to"] = t
            mobs[r["id"]] = {"name": r["name"], "pos": r["pos"], "health": r.get("health"), "from": t, "to": end + 1}
            mob_list.append(mobs[r["id"]])
        elif kind == "mob_gone":
            if r["id"] in mobs:
                mobs.pop(r["id"])["to"] = t
        elif kind == "score":
            scores.append({"t": t, **r["scores"]})
        elif kind == "program":
            who, what = r["player"], r["what"]
            programs.setdefault(who, []).append([t, what])
            if what == "start":
                feed.append([t, "program", f"{who}: program run {r.get('run')} starts"])
            elif what == "error":
                feed.append([t, "error", f"{who}: error: {r.get('message', '')}"])
        elif kind == "event":
            e = r["event"]
            if e.get("event") == "chat":
                who = e.get("player")
                feed.append([t, "chat", (f"<{who}> " if who else "[server] ") + str(e.get("message", ""))])
            elif e.get("event") in WORLD_EVENTS:
                feed.append([t, "world", WORLD_EVENTS[e["event"]](e)])
        elif kind == "end" and r.get("error"):
            feed.append([t, "error", f"recording ended early: {r['error']}"])
    feed.sort(key=lambda f: f[0])
    return {
        "title": h.get("title", h.get("scenario")),
        "episode": h.get("episode"),
        "length": h.get("length", end),
        "duration": end,
        "sides": h.get("sides", {}),
        "map": {**blocks, "ground": GROUND_Y},
        "tracks": tracks,
        "changes": changes,
        "items": item_list,
        "mobs": mob_list,
        "scores": scores,
        "feed": feed,
        "programs": programs,
    }


def script(*names: str) -> str:
    """The page's script: the map (js/replay/map.js), then the page's own files (js/replay/NAME)."""
    folder = resources.files("pillagerbench").joinpath("js/replay")
    return "\n".join(folder.joinpath(name).read_text() for name in ("map.js", *names))


def embedded(data: dict) -> str:
    """The page's data, as the script reads it (a JSON script element that no text can close early)."""
    blob = json.dumps(data, separators=(",", ":")).replace("</", "<\\/")
    return f"<script id='replay-data' type='application/json'>{blob}</script>"


def render(replay: Replay, where: str = "") -> str:
    data = page_data(replay)
    sides = " vs ".join(f"{k} {s.get('team')}" for k, s in data["sides"].items())
    title = f"{data['title']}, episode {data['episode']}: {sides}"
    subtitle = (
        f"{where} · {data['duration']:.1f} s recorded of {data['length']:g} s · "
        f"{sum(len(v) for v in data['tracks'].values())} player positions · {len(data['feed'])} feed lines"
    )
    warning = f"<p class='warn'>{html.escape(replay.problem)}</p>" if replay.problem else ""
    return (
        f"<!doctype html><html><head><meta charset='utf-8'><title>{html.escape(title)}</title>"
        f"<style>{STYLE}</style></head><body>"
        + BODY.format(title=html.escape(title), subtitle=html.escape(subtitle), warning=warning)
        + embedded(data)
        + f"<script>{script('page.js')}</script></body></html>"
    )


def write_replay(episode_dir: Path, out: Path | None = None) -> tuple[Path, Replay]:
    """Write the episode's page to `out` (default: `replay.html` in the episode directory); return
    its path and the recording read."""
    episode_dir = Path(episode_dir)
    replay = load_replay(episode_dir)
    out = Path(out) if out else episode_dir / PAGE
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(render(replay, str(episode_dir)))
    return out, replay


def main(argv: list[str]) -> int:
    if len(argv) != 1 or argv[0].startswith("-"):
        print("usage: pillagerbench replay RUN_DIR/episode_000  (writes replay.html there)", file=sys.stderr)
        return 2
    try:
        out, replay = write_replay(Path(argv[0]))
    except ReplayError as exc:
        print(f"pillagerbench replay: {exc}", file=sys.stderr)
        return 2
    if replay.problem:
        print(f"pillagerbench replay: note: {replay.problem}", file=sys.stderr)
    print(f"replay: {out}")
    return 0
