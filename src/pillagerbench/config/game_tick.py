"""The game's tick as Python reads it, from its one declaration (js/clock/tick.json, which the Node side
reads too): TICK_MS, TICK_S (a tick in game seconds) and TICKS_PER_S (the lockstep clock's tick rate)."""

from __future__ import annotations

import json
from pathlib import Path

DECLARATION = Path(__file__).resolve().parents[1] / "js" / "clock" / "tick.json"
TICK_MS: int = int(json.loads(DECLARATION.read_text())["ms"])
TICK_S = TICK_MS / 1000
TICKS_PER_S = 1000 // TICK_MS
